//! How far a shadowed GPU image is from the CPU reference, in a few numbers,
//! and which configurations are worth their time (the Pareto front).

use crate::reference::{ReferenceImage, luminance};

/// One image's radiance, visibility and coverage, row-major from the top.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// Reflected radiance L (W/m²/sr, linear RGB).
    pub radiance: Vec<[f64; 3]>,
    /// Visibility V ∈ [0, 1].
    pub visibility: Vec<f64>,
    /// 0 where the pixel shows the background.
    pub coverage: Vec<f64>,
}

impl Frame {
    /// The GPU's quantity target (radiance, view `shaded`) and aux target
    /// (V, texel density, max(0, n·l), coverage).
    pub fn from_gpu(quantity: &[[f32; 4]], aux: &[[f32; 4]]) -> Self {
        Self {
            radiance: quantity
                .iter()
                .map(|q| [q[0], q[1], q[2]].map(f64::from))
                .collect(),
            visibility: aux.iter().map(|a| a[0] as f64).collect(),
            coverage: aux.iter().map(|a| a[3] as f64).collect(),
        }
    }

    pub fn from_reference(image: &ReferenceImage) -> Self {
        Self {
            radiance: image.radiance.clone(),
            visibility: image.visibility.iter().map(|&v| v as f64).collect(),
            coverage: image.coverage.iter().map(|&c| c as f64).collect(),
        }
    }

    /// Mean luminance over the covered pixels (W/m²/sr), 0 without any.
    pub fn mean_luminance(&self) -> f64 {
        let (sum, n) = self
            .radiance
            .iter()
            .zip(&self.coverage)
            .filter(|(_, c)| **c > 0.0)
            .fold((0.0, 0usize), |(s, n), (l, _)| (s + luminance(*l), n + 1));
        if n > 0 { sum / n as f64 } else { 0.0 }
    }
}

/// The error of one configuration against the reference.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ErrorMetrics {
    /// Root mean square of the luminance error L − L_ref over the pixels
    /// that show geometry in either image (W/m²/sr).
    pub rmse: f64,
    /// `rmse` over the mean reference luminance of those pixels.
    pub relative_rmse: f64,
    /// The largest |L − L_ref| in luminance (W/m²/sr).
    pub max_abs: f64,
    /// Of the pixels facing the light, the fraction whose shadow state
    /// (V ≥ ½) differs from the reference's.
    pub wrong_shadow_fraction: f64,
    /// Mean |V − V_ref| over the penumbra (see [`Comparison`]); 0 when the
    /// image has none.
    pub penumbra_mean_abs_dv: f64,
    pub penumbra_pixels: usize,
}

/// The reference and the masks every configuration is measured on.
pub struct Comparison {
    reference: Frame,
    /// Covered and facing the light (n·l > 0): where a shadow can be cast.
    facing: Vec<bool>,
    /// Facing pixels where V_ref is fractional or within `PENUMBRA_RADIUS`
    /// pixels of a change of the reference's shadow state.
    penumbra: Vec<bool>,
}

/// Half the width (pixels) of the band around a hard shadow edge that counts
/// as penumbra: a point light's edge is sharp, but a filter's is not.
pub const PENUMBRA_RADIUS: usize = 2;

impl Comparison {
    /// `facing_aux`: the GPU's aux target of the same view, whose n·l and
    /// coverage tell which pixels face the light (the same for every shadow
    /// configuration; the reference's V is 0 both behind the light and in
    /// cast shadow).
    pub fn new(reference: &ReferenceImage, facing_aux: &[[f32; 4]]) -> Self {
        let (width, height) = (reference.width as usize, reference.height as usize);
        let reference = Frame::from_reference(reference);
        let facing: Vec<bool> = facing_aux
            .iter()
            .zip(&reference.coverage)
            .map(|(a, &c)| a[2] > 0.0 && a[3] > 0.0 && c > 0.0)
            .collect();
        let lit = |i: usize| reference.visibility[i] >= 0.5;
        let mut penumbra = vec![false; width * height];
        for y in 0..height {
            for x in 0..width {
                let i = y * width + x;
                if !facing.get(i).copied().unwrap_or(false) {
                    continue;
                }
                let v = reference.visibility[i];
                let fractional = v > 0.01 && v < 0.99;
                let near_edge = || {
                    let (x0, x1) = (
                        x.saturating_sub(PENUMBRA_RADIUS),
                        (x + PENUMBRA_RADIUS).min(width - 1),
                    );
                    let (y0, y1) = (
                        y.saturating_sub(PENUMBRA_RADIUS),
                        (y + PENUMBRA_RADIUS).min(height - 1),
                    );
                    (y0..=y1).any(|yy| {
                        (x0..=x1).any(|xx| facing[yy * width + xx] && lit(yy * width + xx) != lit(i))
                    })
                };
                penumbra[i] = fractional || near_edge();
            }
        }
        Self {
            reference,
            facing,
            penumbra,
        }
    }

    pub fn reference(&self) -> &Frame {
        &self.reference
    }

    /// The error of `frame` (same size as the reference).
    pub fn measure(&self, frame: &Frame) -> ErrorMetrics {
        let r = &self.reference;
        let (mut sum2, mut sum_ref, mut max_abs, mut covered) = (0.0, 0.0, 0.0_f64, 0usize);
        for i in 0..r.radiance.len().min(frame.radiance.len()) {
            if r.coverage[i] <= 0.0 && frame.coverage[i] <= 0.0 {
                continue;
            }
            let l_ref = luminance(r.radiance[i]);
            let error = luminance(frame.radiance[i]) - l_ref;
            let error = if error.is_finite() { error } else { f64::MAX.sqrt() };
            sum2 += error * error;
            sum_ref += l_ref;
            max_abs = max_abs.max(error.abs());
            covered += 1;
        }
        let (mut facing, mut wrong, mut penumbra, mut sum_dv) = (0usize, 0usize, 0usize, 0.0);
        for (i, _) in self.facing.iter().enumerate().filter(|(_, f)| **f) {
            let (v, v_ref) = (frame.visibility[i], r.visibility[i]);
            facing += 1;
            wrong += usize::from((v >= 0.5) != (v_ref >= 0.5));
            if self.penumbra[i] {
                penumbra += 1;
                sum_dv += (v - v_ref).abs().min(1.0);
            }
        }
        let ratio = |a: f64, b: f64| if b > 0.0 { a / b } else { 0.0 };
        let rmse = ratio(sum2, covered as f64).sqrt();
        ErrorMetrics {
            rmse,
            relative_rmse: ratio(rmse, ratio(sum_ref, covered as f64)),
            max_abs,
            wrong_shadow_fraction: ratio(wrong as f64, facing as f64),
            penumbra_mean_abs_dv: ratio(sum_dv, penumbra as f64),
            penumbra_pixels: penumbra,
        }
    }

    /// Signed luminance error L − L_ref per pixel (W/m²/sr), 0 on background.
    pub fn signed_error(&self, frame: &Frame) -> Vec<f64> {
        let r = &self.reference;
        (0..r.radiance.len())
            .map(|i| {
                let e = luminance(frame.radiance[i]) - luminance(r.radiance[i]);
                if e.is_finite() { e } else { 0.0 }
            })
            .collect()
    }
}

/// For each (time, error) point, whether no other point is at least as good
/// in both and better in one.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<bool> {
    points
        .iter()
        .map(|&(t, e)| {
            !points
                .iter()
                .any(|&(t2, e2)| t2 <= t && e2 <= e && (t2 < t || e2 < e))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::RenderStats;

    /// A 6×1 reference: lit, lit, lit | shadowed, shadowed, background.
    fn reference() -> ReferenceImage {
        ReferenceImage {
            width: 6,
            height: 1,
            radiance: vec![[1.0; 3], [1.0; 3], [1.0; 3], [0.0; 3], [0.0; 3], [0.0; 3]],
            visibility: vec![1.0, 1.0, 1.0, 0.0, 0.0, 0.0],
            coverage: vec![1.0, 1.0, 1.0, 1.0, 1.0, 0.0],
            noise: vec![0.0; 6],
            noise_known: true,
            stats: RenderStats::default(),
        }
    }

    fn facing() -> Vec<[f32; 4]> {
        let mut aux = vec![[1.0, 0.0, 1.0, 1.0]; 6];
        aux[5] = [0.0; 4];
        aux
    }

    #[test]
    fn the_reference_scores_zero() {
        let image = reference();
        let comparison = Comparison::new(&image, &facing());
        let metrics = comparison.measure(&Frame::from_reference(&image));
        assert_eq!(metrics.rmse, 0.0);
        assert_eq!(metrics.max_abs, 0.0);
        assert_eq!(metrics.wrong_shadow_fraction, 0.0);
        assert_eq!(metrics.penumbra_mean_abs_dv, 0.0);
        // Pixels 1..=4 lie within 2 pixels of the edge between 2 and 3.
        assert_eq!(metrics.penumbra_pixels, 4);
    }

    #[test]
    fn a_shadow_one_pixel_too_wide_is_measured() {
        let image = reference();
        let comparison = Comparison::new(&image, &facing());
        let mut frame = Frame::from_reference(&image);
        frame.radiance[2] = [0.0; 3];
        frame.visibility[2] = 0.0;
        let metrics = comparison.measure(&frame);
        // One of 5 covered pixels is off by 1 in luminance.
        assert!((metrics.rmse - (1.0_f64 / 5.0).sqrt()).abs() < 1e-12);
        assert!((metrics.max_abs - 1.0).abs() < 1e-12);
        assert!((metrics.relative_rmse - (0.2_f64).sqrt() / 0.6).abs() < 1e-12);
        assert!((metrics.wrong_shadow_fraction - 0.2).abs() < 1e-12);
        assert!((metrics.penumbra_mean_abs_dv - 0.25).abs() < 1e-12);
    }

    #[test]
    fn the_front_is_the_non_dominated_set() {
        let points = [
            (1.0, 5.0),
            (2.0, 3.0),
            (2.0, 4.0),
            (3.0, 3.0),
            (4.0, 0.0),
            (0.5, 9.0),
        ];
        assert_eq!(pareto_front(&points), [true, true, false, false, true, true]);
        // Equal points are both on the front.
        assert_eq!(pareto_front(&[(1.0, 1.0), (1.0, 1.0)]), [true, true]);
    }
}
