//! The WGSL of each pass: `shaders/common.wgsl` (layouts and the physics),
//! tables generated here (Poisson disc, colour ramps), then the pass's own file.

/// Points of the Poisson disc used by `poisson` and `pcss`.
pub const POISSON_POINTS: usize = 64;

/// One shader module's source, ready for `create_shader_module` or naga.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shader {
    Shadow,
    Blur,
    Shade,
    Reduce,
    Display,
    Lines,
    /// The hard-case grid of `lumlab stability` (a compute pass).
    Stability,
}

impl Shader {
    pub const ALL: [Shader; 7] = [
        Self::Shadow,
        Self::Blur,
        Self::Shade,
        Self::Reduce,
        Self::Display,
        Self::Lines,
        Self::Stability,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Self::Shadow => "shadow.wgsl",
            Self::Blur => "blur.wgsl",
            Self::Shade => "shade.wgsl",
            Self::Reduce => "reduce.wgsl",
            Self::Display => "display.wgsl",
            Self::Lines => "lines.wgsl",
            Self::Stability => "stability.wgsl",
        }
    }

    fn own_source(self) -> &'static str {
        match self {
            Self::Shadow => include_str!("../../shaders/shadow.wgsl"),
            Self::Blur => include_str!("../../shaders/blur.wgsl"),
            Self::Shade => include_str!("../../shaders/shade.wgsl"),
            Self::Reduce => include_str!("../../shaders/reduce.wgsl"),
            Self::Display => include_str!("../../shaders/display.wgsl"),
            Self::Lines => include_str!("../../shaders/lines.wgsl"),
            Self::Stability => include_str!("../../shaders/stability.wgsl"),
        }
    }

    /// The complete WGSL source.
    pub fn source(self) -> String {
        let mut source = String::from(include_str!("../../shaders/common.wgsl"));
        source += &poisson_wgsl();
        source += &super::colormap::wgsl();
        source += self.own_source();
        source
    }

    pub fn module(self, device: &wgpu::Device) -> wgpu::ShaderModule {
        device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(self.name()),
            source: wgpu::ShaderSource::Wgsl(self.source().into()),
        })
    }
}

/// A Poisson disc of unit radius, built by best-candidate sampling with a
/// fixed seed: every prefix of it is itself well spread, so a filter may use
/// the first N points.
pub fn poisson_disc() -> [[f32; 2]; POISSON_POINTS] {
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut next = move || {
        // xorshift64*: deterministic, good enough for candidate positions.
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        (state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 40) as f32 / (1u64 << 24) as f32
    };
    let mut points: Vec<[f32; 2]> = Vec::with_capacity(POISSON_POINTS);
    while points.len() < POISSON_POINTS {
        let mut best = [0.0, 0.0];
        let mut best_distance = -1.0;
        for _ in 0..(8 * (points.len() + 1)) {
            // A uniform point in the unit disc.
            let (r, a) = (next().sqrt(), next() * std::f32::consts::TAU);
            let c = [r * a.cos(), r * a.sin()];
            let d = points
                .iter()
                .map(|p| (p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2))
                .fold(f32::INFINITY, f32::min);
            if d > best_distance {
                best_distance = d;
                best = c;
            }
        }
        points.push(best);
    }
    std::array::from_fn(|i| points[i])
}

fn poisson_wgsl() -> String {
    let points = poisson_disc()
        .iter()
        .map(|p| format!("vec2<f32>({:?}, {:?})", p[0], p[1]))
        .collect::<Vec<_>>()
        .join(", ");
    format!(
        "var<private> POISSON_DISC: array<vec2<f32>, {POISSON_POINTS}> = array<vec2<f32>, {POISSON_POINTS}>({points});\n"
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn poisson_points_are_in_the_disc_and_spread() {
        let points = poisson_disc();
        assert!(points.iter().all(|p| p[0] * p[0] + p[1] * p[1] <= 1.0));
        let mut min = f32::INFINITY;
        for (i, a) in points.iter().enumerate() {
            for b in &points[i + 1..] {
                min = min.min(((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt());
            }
        }
        // 64 points in the unit disc: a random set would have pairs far closer.
        assert!(min > 0.12, "closest pair {min}");
    }
}
