//! What the app reads back from the viewport's frames without blocking: a
//! pixel for the probe (started by `GpuViews::request_probe`). Half A's
//! whole frame, for the error statistics and the exposure, is its quantity
//! target alone (`GpuViews::request_frame`).

use super::probe::{GpuSample, quantity_is_radiance};
use crate::gpu::PendingTexels;
use crate::gpu::readback::ReadState;
use crate::settings::{DebugView, Visibility};

/// A pixel of a half being read back for the probe.
pub struct PendingProbe {
    view: DebugView,
    method: Visibility,
    aux: PendingTexels,
    quantity: PendingTexels,
    aux_value: Option<[f32; 4]>,
    quantity_value: Option<[f32; 4]>,
}

impl PendingProbe {
    /// The probe's reads of a pixel of a frame showing `view`, V from `method`.
    pub fn new(view: DebugView, method: Visibility, aux: PendingTexels, quantity: PendingTexels) -> Self {
        Self {
            view,
            method,
            aux,
            quantity,
            aux_value: None,
            quantity_value: None,
        }
    }

    /// The GPU's values at the pixel once both reads are back.
    pub fn poll(&mut self) -> ReadState<GpuSample> {
        let reads = [
            (&self.aux, &mut self.aux_value),
            (&self.quantity, &mut self.quantity_value),
        ];
        if !collect(reads, |texels| texels.first().copied().unwrap_or_default()) {
            return ReadState::Failed;
        }
        match (self.aux_value, self.quantity_value) {
            (Some(aux), Some(quantity)) => ReadState::Ready(GpuSample {
                visibility: aux[0],
                method: self.method,
                texel_density: aux[1],
                radiance: quantity_is_radiance(self.view).then_some([quantity[0], quantity[1], quantity[2]]),
                // Negative: no illuminant, no ΔE (gpu::delta_e).
                delta_e: (self.view == DebugView::DeltaE && quantity[0] >= 0.0).then_some(quantity[0]),
            }),
            _ => ReadState::Waiting,
        }
    }
}

/// Polls the reads whose values are not back yet, keeping each value as
/// `keep` makes it from the texels; false when a read failed.
fn collect<T>(reads: [(&PendingTexels, &mut Option<T>); 2], keep: impl Fn(Vec<[f32; 4]>) -> T) -> bool {
    for (pending, slot) in reads {
        if slot.is_none() {
            match pending.poll() {
                ReadState::Waiting => {}
                ReadState::Ready(texels) => *slot = Some(keep(texels)),
                ReadState::Failed => return false,
            }
        }
    }
    true
}
