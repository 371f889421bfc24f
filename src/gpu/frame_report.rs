//! What a frame did ([`FrameReport`]): the shadow map's layout and draws, the
//! camera's planes, the meshes drawn; for the Timings panel, the report and
//! the tests.

use super::light_frustum::{LayoutKind, ShadowLayout};

/// What a frame did, for the timings panel, the report and the tests.
#[derive(Clone, Debug, Default)]
pub struct FrameReport {
    pub size: (u32, u32),
    /// This frame drew its shadow map (otherwise it read one already drawn,
    /// by this view or by another that shares the scene).
    pub shadow_redrawn: bool,
    /// Nothing this frame reads the shadow map (ray-traced visibility, any
    /// view but `depth`): it was neither drawn nor looked for.
    pub shadow_map_unused: bool,
    /// The light's layers; None when shadows are off or nothing is drawn.
    pub layout: Option<ShadowLayout>,
    /// Casters drawn per layer by the current shadow map.
    pub casters_per_layer: Vec<usize>,
    /// Objects that cast shadows at all.
    pub casters_total: usize,
    /// Objects inside the camera's frustum.
    pub visible_objects: usize,
    /// Shadow-map resolution in use (texels per side).
    pub resolution: u32,
    /// Why the resolution is below the requested one, if it is.
    pub resolution_note: Option<String>,
    /// Camera near and far planes (m), fitted to the scene.
    pub camera_near_far: (f64, f64),
    /// The triangles drawn when the frame drew the simplified meshes (None:
    /// the full ones).
    pub simplified_triangles: Option<usize>,
    /// The block side (texels) of the depth ranges the filter read this
    /// frame (gpu::depth_ranges); None: every tap was tested.
    pub depth_ranges: Option<u32>,
}

impl FrameReport {
    /// "single frustum" or "cube, k of 6 faces".
    pub fn layout_summary(&self) -> String {
        match &self.layout {
            None => "no shadow map".into(),
            Some(l) if l.kind == LayoutKind::Single => "one frustum fitted to the scene".into(),
            Some(l) => format!("cube map, {} of 6 faces drawn", l.active_mask().count_ones()),
        }
    }
}
