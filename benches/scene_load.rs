//! Load time of a large glTF scene: a GLB of a million triangles (a field of
//! spheres, one mesh each) written to a temporary folder, then loaded,
//! flattened and checked as the lab does at start-up.
//!
//! Then the peak memory of the same load, in a fresh process that only
//! loads it: `lumlab info` on the same file (its last line).

use criterion::{Criterion, criterion_group, criterion_main};
use lumlab::scene;
use std::hint::black_box;
use std::time::Duration;

const TRIANGLES: usize = 1_000_000;

fn load_a_million_triangles(c: &mut Criterion) {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let path = dir.path().join("million.glb");
    let built = scene::stress::sphere_field(TRIANGLES);
    std::fs::write(&path, scene::gltf::to_glb(&built)).expect("writing the scene");
    let triangles = built.triangle_count();
    drop(built);
    let mut group = c.benchmark_group("scene_load");
    group.sample_size(10).measurement_time(Duration::from_secs(20));
    group.bench_function(format!("glb_{triangles}_triangles"), |b| {
        b.iter(|| {
            let loaded = scene::load(black_box(&path)).expect("the scene loads");
            assert_eq!(loaded.triangle_count(), triangles);
            loaded
        })
    });
    group.finish();
    let info = std::process::Command::new(env!("CARGO_BIN_EXE_lumlab"))
        .arg("info")
        .arg("--scene")
        .arg(&path)
        .output()
        .expect("lumlab info runs");
    let text = String::from_utf8_lossy(if info.status.success() {
        &info.stdout
    } else {
        &info.stderr
    });
    println!("lumlab info: {}", text.lines().last().unwrap_or("(no output)"));
}

criterion_group!(benches, load_a_million_triangles);
criterion_main!(benches);
