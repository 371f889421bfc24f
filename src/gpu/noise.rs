//! The noise left in a sphere light's ray-traced mean, measured on the image
//! itself: the mean of N frames against the mean of its first K, kept from
//! an earlier frame (K the last power of two below N). With independent
//! frames Var(m_N − m_K) = σ² (1/K − 1/N), σ²/N being m_N's variance, so
//! RMS(m_N − m_K) · √(K / (N − K)) estimates m_N's standard error.
//!
//! The frames' low-discrepancy samples are not independent, and their mean
//! converges faster than 1/√N: on the default scene under a sphere light of
//! R = 0.3 m this estimate of V's error is 1.1–1.7× the error measured
//! against the reference from 2 to 256 frames (tests/gpu_raytrace.rs), where
//! the bound σ ≤ 0.5 / √(N·S) overstates it up to 45×.

use super::readback::ReadState;
use super::targets::PendingTexels;
use crate::physics::colour::luminance;

/// The noise left in the mean of `frames` frames.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NoiseEstimate {
    /// N: frames in the mean it was measured on.
    pub frames: u32,
    /// K: frames in the earlier mean it was compared with.
    pub earlier_frames: u32,
    /// The RMS standard error of the luminance of the quantity over the
    /// covered pixels, over their mean luminance.
    pub relative: f64,
}

/// The RMS standard error of a mean of `n` frames, estimated from pairs
/// (its value, the mean of its first `k` frames' value) over the pixels;
/// None without pairs or unless 0 < k < n.
pub fn standard_error(pairs: impl IntoIterator<Item = (f64, f64)>, n: u32, k: u32) -> Option<f64> {
    if k == 0 || k >= n {
        return None;
    }
    let (count, sum) = pairs.into_iter().fold((0usize, 0.0), |(c, s), (later, earlier)| {
        (c + 1, s + (later - earlier).powi(2))
    });
    (count > 0).then(|| (sum / count as f64 * f64::from(k) / f64::from(n - k)).sqrt())
}

/// A run of the accumulation: a number no other run of any renderer has.
pub fn new_run() -> u64 {
    static RUNS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    RUNS.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
}

/// The reads and the estimate of one renderer's accumulation.
#[derive(Default)]
pub struct NoiseProbe {
    run: u64,
    /// The frame count of the last read asked for in this run.
    last_read: u32,
    /// Reads on their way, oldest first.
    pending: std::collections::VecDeque<(u32, PendingTexels)>,
    /// The luminance of the last mean read back (NaN where nothing is
    /// covered), and its frame count.
    earlier: Option<(u32, Vec<f64>)>,
    estimate: Option<NoiseEstimate>,
}

impl NoiseProbe {
    /// Whether a mean of `frames` frames in `run` is read back: from two
    /// frames on, at each power of two, and at the last frame.
    pub fn wants(&mut self, run: u64, frames: u32, complete: bool) -> bool {
        if run != self.run {
            *self = Self {
                run,
                ..Self::default()
            };
        }
        let due = frames >= 2 && (frames.is_power_of_two() || complete) && frames != self.last_read;
        if due {
            self.last_read = frames;
        }
        due
    }

    /// Keeps the read of the mean of `frames` frames (see [`Self::wants`]).
    pub fn read(&mut self, frames: u32, texels: PendingTexels) {
        self.pending.push_back((frames, texels));
    }

    /// Picks up the reads that are back, in order; true while one is on
    /// its way.
    pub fn poll(&mut self) -> bool {
        while let Some((frames, texels)) = self.pending.front() {
            let texels = match texels.poll() {
                ReadState::Waiting => return true,
                ReadState::Failed => Vec::new(),
                ReadState::Ready(texels) => texels,
            };
            let frames = *frames;
            self.pending.pop_front();
            self.measure(frames, &texels);
        }
        false
    }

    /// Measures the mean of `frames` frames, read back as `texels`, against
    /// the earlier one, and keeps it where `frames` is a power of two.
    fn measure(&mut self, frames: u32, texels: &[[f32; 4]]) {
        let luminance: Vec<f64> = texels
            .iter()
            .map(|t| {
                if t[3] > 0.0 {
                    luminance([t[0], t[1], t[2]].map(f64::from))
                } else {
                    f64::NAN
                }
            })
            .collect();
        if let Some((k, earlier)) = &self.earlier
            && earlier.len() == luminance.len()
        {
            let covered = || {
                luminance
                    .iter()
                    .zip(earlier)
                    .filter(|(l, e)| l.is_finite() && e.is_finite())
                    .map(|(&l, &e)| (l, e))
            };
            let mean = covered().map(|(l, _)| l).sum::<f64>() / covered().count().max(1) as f64;
            self.estimate = standard_error(covered(), frames, *k)
                .filter(|_| mean > 0.0)
                .map(|error| NoiseEstimate {
                    frames,
                    earlier_frames: *k,
                    relative: error / mean,
                });
        }
        if frames.is_power_of_two() {
            self.earlier = Some((frames, luminance));
        }
    }

    /// The last estimate of `run`'s noise.
    pub fn estimate(&self, run: u64) -> Option<NoiseEstimate> {
        self.estimate.filter(|_| self.run == run)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn independent_frames_give_their_mean_s_standard_error() {
        // Frames of σ = 1 noise per pixel: the mean of n has σ / √n.
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        let mut normal = move || {
            // Sum of 12 uniforms − 6: mean 0, variance 1.
            (0..12)
                .map(|_| {
                    state ^= state << 13;
                    state ^= state >> 7;
                    state ^= state << 17;
                    (state >> 11) as f64 / (1u64 << 53) as f64
                })
                .sum::<f64>()
                - 6.0
        };
        let (n, k) = (64u32, 16u32);
        let pairs: Vec<(f64, f64)> = (0..20_000)
            .map(|_| {
                let frames: Vec<f64> = (0..n).map(|_| normal()).collect();
                let mean = |m: u32| frames[..m as usize].iter().sum::<f64>() / f64::from(m);
                (mean(n), mean(k))
            })
            .collect();
        let error = standard_error(pairs, n, k).unwrap();
        let expected = 1.0 / f64::from(n).sqrt();
        assert!(
            (error / expected - 1.0).abs() < 0.03,
            "{error} against {expected}"
        );
    }

    #[test]
    fn no_estimate_without_an_earlier_mean_or_pixels() {
        assert_eq!(standard_error([(1.0, 0.0)], 4, 4), None);
        assert_eq!(standard_error([(1.0, 0.0)], 4, 0), None);
        assert_eq!(standard_error([], 4, 2), None);
    }

    #[test]
    fn reads_at_powers_of_two_and_at_the_last_frame_once_each() {
        let mut probe = NoiseProbe::default();
        let run = new_run();
        let read: Vec<u32> = (1..=100).filter(|&n| probe.wants(run, n, n == 100)).collect();
        assert_eq!(read, [2, 4, 8, 16, 32, 64, 100]);
        assert!(!probe.wants(run, 100, true), "a held image is not read again");
        assert!(probe.wants(new_run(), 2, false), "a new run reads anew");
    }
}
