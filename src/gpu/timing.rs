//! GPU time of each pass through timestamp queries, where the adapter has
//! them; the caller falls back to wall time around submit + wait otherwise.

use std::sync::Arc;
use std::sync::atomic::{AtomicU8, Ordering};

/// The passes timed, each with a begin and an end timestamp.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pass {
    Shadow = 0,
    Blur = 1,
    Shade = 2,
    Display = 3,
}

const PASSES: u32 = 4;

/// Milliseconds per pass; None when the pass did not run this frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PassTimes {
    pub shadow_ms: Option<f64>,
    pub blur_ms: Option<f64>,
    pub shade_ms: Option<f64>,
    pub display_ms: Option<f64>,
}

impl std::fmt::Display for PassTimes {
    /// "12.3 ms (shadow 1.0, shade 10.2, display 1.1)": passes that ran.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let parts: Vec<String> = [
            ("shadow", self.shadow_ms),
            ("prefilter", self.blur_ms),
            ("shade", self.shade_ms),
            ("display", self.display_ms),
        ]
        .iter()
        .filter_map(|(name, ms)| ms.map(|ms| format!("{name} {ms:.1}")))
        .collect();
        write!(f, "{:.1} ms ({})", self.total_ms(), parts.join(", "))
    }
}

impl PassTimes {
    pub fn total_ms(&self) -> f64 {
        [self.shadow_ms, self.blur_ms, self.shade_ms, self.display_ms]
            .iter()
            .flatten()
            .sum()
    }
}

const IDLE: u8 = 0;
const MAPPING: u8 = 1;
const MAPPED: u8 = 2;

pub struct GpuTimer {
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    readback: wgpu::Buffer,
    state: Arc<AtomicU8>,
    period_ns: f64,
    /// Which passes wrote their timestamps in the frame being encoded.
    written: [bool; PASSES as usize],
    /// Passes of the frame whose readback is under way.
    pending: [bool; PASSES as usize],
    pub last: Option<PassTimes>,
}

impl GpuTimer {
    /// None when the device has no timestamp queries.
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Option<Self> {
        if !device.features().contains(wgpu::Features::TIMESTAMP_QUERY) {
            return None;
        }
        let size = (2 * PASSES as u64) * 8;
        let buffer = |label: &str, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage,
                mapped_at_creation: false,
            })
        };
        Some(Self {
            queries: device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("pass timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count: 2 * PASSES,
            }),
            resolve: buffer(
                "timestamp resolve",
                wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            ),
            readback: buffer(
                "timestamp readback",
                wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            ),
            state: Arc::new(AtomicU8::new(IDLE)),
            period_ns: queue.get_timestamp_period() as f64,
            written: [false; PASSES as usize],
            pending: [false; PASSES as usize],
            last: None,
        })
    }

    /// Starts a frame: nothing written yet.
    pub fn begin_frame(&mut self) {
        self.written = [false; PASSES as usize];
    }

    /// Timestamp writes for a render or compute pass: `first` and `last` say
    /// whether this pass begins or ends the timed span (a span may cover
    /// several passes, e.g. the six cube faces).
    /// None for the passes in the middle of a span (wgpu wants at least one index).
    pub fn writes(
        &mut self,
        pass: Pass,
        first: bool,
        last: bool,
    ) -> Option<wgpu::RenderPassTimestampWrites<'_>> {
        let i = pass as u32;
        if last {
            self.written[i as usize] = true;
        }
        (first || last).then_some(wgpu::RenderPassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: first.then_some(2 * i),
            end_of_pass_write_index: last.then_some(2 * i + 1),
        })
    }

    /// Resolves the queries and copies them for reading, unless the previous
    /// frame's readback is still in flight (then this frame goes untimed).
    pub fn end_frame(&mut self, encoder: &mut wgpu::CommandEncoder) -> bool {
        if self.state.load(Ordering::Acquire) != IDLE {
            return false;
        }
        encoder.resolve_query_set(&self.queries, 0..2 * PASSES, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.readback, 0, self.resolve.size());
        self.pending = self.written;
        true
    }

    /// After the submission that `end_frame` returned true for: asks for the
    /// readback without blocking.
    pub fn request_readback(&self) {
        self.state.store(MAPPING, Ordering::Release);
        let state = Arc::clone(&self.state);
        self.readback
            .slice(..)
            .map_async(wgpu::MapMode::Read, move |result| {
                state.store(if result.is_ok() { MAPPED } else { IDLE }, Ordering::Release);
            });
    }

    /// Reads the times if the readback is done (call after a device poll).
    pub fn collect(&mut self) -> Option<PassTimes> {
        if self.state.load(Ordering::Acquire) != MAPPED {
            return None;
        }
        let ticks: Vec<u64> = {
            let data = self.readback.slice(..).get_mapped_range().ok()?;
            bytemuck::cast_slice(&data).to_vec()
        };
        self.readback.unmap();
        self.state.store(IDLE, Ordering::Release);
        let ms = |i: usize| {
            self.pending[i]
                .then(|| ticks[2 * i + 1].saturating_sub(ticks[2 * i]) as f64 * self.period_ns / 1e6)
        };
        let times = PassTimes {
            shadow_ms: ms(Pass::Shadow as usize),
            blur_ms: ms(Pass::Blur as usize),
            shade_ms: ms(Pass::Shade as usize),
            display_ms: ms(Pass::Display as usize),
        };
        self.last = Some(times);
        Some(times)
    }
}
