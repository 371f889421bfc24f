//! Shared by the integration tests: a GPU (failing loudly without one), small
//! scenes built from `scene::shapes`, and rendering helpers.
#![allow(dead_code)]

pub mod gpu_thread;
pub mod kernel;

use glam::Vec3;
use lumlab::gpu::{FrameReport, GpuContext, Renderer};
use lumlab::scene::shapes::{cuboid, ground, ground_grid};
use lumlab::scene::{Aabb, Material, Object, Scene};
use lumlab::settings::Settings;

/// The test's GPU; no adapter is a failure that says what to install.
pub fn gpu() -> GpuContext {
    GpuContext::headless().unwrap_or_else(|e| panic!("GPU test needs an adapter: {e}"))
}

pub fn material(color: Vec3) -> Material {
    Material {
        name: "test".into(),
        base_color: color.extend(1.0),
        ..Material::default()
    }
}

/// A square ground of side `size` at y = 0, white (c = 1).
pub fn plane_scene(size: f32) -> Scene {
    scene_of(ground(Vec3::ZERO, size))
}

/// The plane split into quads of about 1 m: small triangles keep the
/// rasterizer's interpolation precise enough for lobes up to m = 10^6.
pub fn fine_plane_scene(size: f32) -> Scene {
    scene_of(ground_grid(Vec3::ZERO, size, size.ceil() as u32))
}

fn scene_of(mesh: lumlab::scene::Mesh) -> Scene {
    Scene {
        objects: vec![Object::new("ground", mesh, 0)],
        materials: vec![material(Vec3::ONE)],
        ..Scene::default()
    }
}

/// The plane with a box occluder.
pub fn occluder_scene(size: f32, occluder: Aabb) -> Scene {
    let mut scene = plane_scene(size);
    scene.objects.push(Object::new("occluder", cuboid(occluder), 0));
    scene
}

pub fn settings(width: u32, height: u32) -> Settings {
    let mut s = Settings::default();
    s.image.width = width;
    s.image.height = height;
    s.material.use_scene_materials = false;
    s
}

/// One frame: the report, the quantity and the aux target.
pub fn render(
    gpu: &GpuContext,
    scene: &Scene,
    settings: &Settings,
) -> (FrameReport, Vec<[f32; 4]>, Vec<[f32; 4]>) {
    let mut renderer = Renderer::new(&gpu.adapter, &gpu.device, &gpu.queue, scene);
    let report = renderer.render(settings, (settings.image.width, settings.image.height));
    (report, renderer.read_quantity(), renderer.read_aux())
}

/// Where the ray through pixel (i, j) meets the plane y = 0, if in front.
pub fn plane_hit(settings: &Settings, i: u32, j: u32) -> Option<glam::DVec3> {
    plane_hit_at(settings, i as f64 + 0.5, j as f64 + 0.5)
}

/// Where the ray through image point (`x`, `y`) (pixels from the top-left
/// corner) meets the plane y = 0.
pub fn plane_hit_at(settings: &Settings, x: f64, y: f64) -> Option<glam::DVec3> {
    let camera = lumlab::scene::Camera {
        eye: settings.camera.eye,
        target: settings.camera.target,
        fovy_deg: settings.camera.fovy_deg,
    };
    let d = camera.ray_direction(x, y, settings.image.width, settings.image.height);
    let eye = camera.eye.as_dvec3();
    let t = -eye.y / d.y;
    (t > 0.0).then(|| eye + d * t)
}

/// How far from its centre (pixels) a rasterizer may evaluate a pixel's
/// attributes: Vulkan snaps vertex positions to a grid of
/// 2^−subPixelPrecisionBits pixel, 8 bits on NVIDIA (lavapipe's grid is finer),
/// so the interpolated position is that of a point up to 1/256 pixel away.
/// Where L changes by tens of percent from one pixel to the next (a sharp
/// lobe seen closely), that alone is more than 1e-3 of L.
pub const SUBPIXEL_PX: f64 = 1.0 / 256.0;

/// The range of `value` over the points within `SUBPIXEL_PX` of (`x`, `y`)
/// on each axis (the corners and edge midpoints of that square, and its
/// centre): where a rasterizer's pixel may land.
pub fn subpixel_range(x: f64, y: f64, value: impl Fn(f64, f64) -> f64) -> (f64, f64) {
    let offsets = [-SUBPIXEL_PX, 0.0, SUBPIXEL_PX];
    let mut range = (f64::INFINITY, f64::NEG_INFINITY);
    for dy in offsets {
        for dx in offsets {
            let v = value(x + dx, y + dy);
            range = (range.0.min(v), range.1.max(v));
        }
    }
    range
}

/// Does the segment from `p` to `q` pass through the box (slab test, f64)?
pub fn segment_hits_box(p: glam::DVec3, q: glam::DVec3, b: &Aabb) -> bool {
    let d = q - p;
    let (mut t0, mut t1): (f64, f64) = (1e-9, 1.0 - 1e-9);
    for axis in 0..3 {
        let (lo, hi) = (b.min[axis] as f64, b.max[axis] as f64);
        if d[axis].abs() < 1e-300 {
            if p[axis] < lo || p[axis] > hi {
                return false;
            }
            continue;
        }
        let (a, c) = ((lo - p[axis]) / d[axis], (hi - p[axis]) / d[axis]);
        t0 = t0.max(a.min(c));
        t1 = t1.min(a.max(c));
    }
    t0 <= t1
}

pub fn aabb(min: [f32; 3], max: [f32; 3]) -> Aabb {
    Aabb {
        min: Vec3::from(min),
        max: Vec3::from(max),
    }
}
