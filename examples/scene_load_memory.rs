//! Peak memory and time of loading a million-triangle GLB, measured in a
//! fresh process so that building the file does not count:
//! `cargo run --release --example scene_load_memory [TRIANGLES]`.
//! (Linux: the peak is VmHWM from /proc/self/status.)

use lumlab::scene;
use std::path::Path;
use std::process::Command;
use std::time::Instant;

/// A line of /proc/self/status, in MiB.
fn status_mib(key: &str) -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with(key))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}

fn load(path: &Path) -> anyhow::Result<()> {
    let before = status_mib("VmHWM:").unwrap_or(f64::NAN);
    let start = Instant::now();
    let loaded = scene::load(path)?;
    let seconds = start.elapsed().as_secs_f64();
    let peak = status_mib("VmHWM:").unwrap_or(f64::NAN);
    let file_mib = std::fs::metadata(path)?.len() as f64 / (1024.0 * 1024.0);
    println!(
        "loaded {} triangles, {} objects from a {file_mib:.1} MiB GLB in {seconds:.3} s; \
         peak resident memory {peak:.0} MiB ({before:.0} MiB before loading)",
        loaded.triangle_count(),
        loaded.objects.len(),
    );
    Ok(())
}

fn main() -> anyhow::Result<()> {
    let mut args = std::env::args().skip(1);
    match args.next().as_deref() {
        Some("--load") => load(Path::new(&args.next().unwrap_or_default())),
        other => {
            let triangles = other.map_or(Ok(1_000_000), str::parse)?;
            let dir = tempfile::tempdir()?;
            let path = dir.path().join("field.glb");
            std::fs::write(
                &path,
                scene::gltf::to_glb(&scene::stress::sphere_field(triangles)),
            )?;
            let status = Command::new(std::env::current_exe()?)
                .arg("--load")
                .arg(&path)
                .status()?;
            anyhow::ensure!(status.success(), "the loading process failed");
            Ok(())
        }
    }
}
