//! What a command will cost, checked before the work starts: the GPU
//! images against the adapter's limits and a memory budget, the CPU
//! reference's time and memory against thresholds (run; ask for `--yes`;
//! refuse with the numbers).

use super::usage;
use crate::input::human_bytes;
use crate::reference::ReferenceOptions;
use crate::settings::Settings;

/// GPU bytes per image pixel: the HDR quantity and aux targets (16 B each
/// at most), the depth buffer (4), the display target (4), the comparison
/// image (16) and the readback buffer (16).
const GPU_BYTES_PER_PIXEL: u64 = 72;
/// GPU memory the image targets may take; the shadow map has its own budget
/// (`gpu::shadow::MEMORY_BUDGET_BYTES`), within which it is clamped.
pub const GPU_IMAGE_BUDGET_BYTES: u64 = 6 << 30;

/// CPU bytes per pixel of a reference render: the tiles' samples, the
/// assembled image and the one converted for writing.
const REFERENCE_BYTES_PER_PIXEL: u64 = 112;
/// CPU bytes per triangle: the flattened scene, the BVH and its triangles.
const REFERENCE_BYTES_PER_TRIANGLE: u64 = 256;
/// Rays a core traces per second, on the slow side: the default scene
/// traces about 0.7 million a core in a debug build on 2 shared cores, a
/// few million in a release build.
const RAYS_PER_SECOND_PER_CORE: f64 = 1.5e6;

/// Above either, `--yes` is needed.
pub const CONFIRM_SECONDS: f64 = 600.0;
pub const CONFIRM_BYTES: u64 = 4 << 30;
/// Above this even `--yes` is refused (as is more memory than the machine has).
pub const REFUSE_SECONDS: f64 = 24.0 * 3600.0;

/// A guess at a piece of work's cost.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Estimate {
    pub seconds: f64,
    pub bytes: u64,
}

/// The reference render's rays, time on this machine's cores and memory.
pub fn reference(settings: &Settings, options: &ReferenceOptions, triangles: usize) -> Estimate {
    let pixels = settings.image.width as f64 * settings.image.height as f64;
    let shadow_rays = if !settings.shadow.enabled {
        0.0
    } else if settings.light.is_sphere() {
        options.light_samples as f64
    } else {
        1.0
    };
    let rays = pixels * options.spp as f64 * (1.0 + shadow_rays);
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get()) as f64;
    Estimate {
        seconds: rays / (RAYS_PER_SECOND_PER_CORE * cores),
        bytes: (pixels as u64) * REFERENCE_BYTES_PER_PIXEL + triangles as u64 * REFERENCE_BYTES_PER_TRIANGLE,
    }
}

/// Runs, asks for `--yes`, or refuses, by the estimate.
pub fn check_cpu(what: &str, estimate: Estimate, yes: bool) -> anyhow::Result<()> {
    let memory = physical_memory_bytes();
    let numbers = format!(
        "{what} needs about {} and {} of memory",
        duration(estimate.seconds),
        human_bytes(estimate.bytes)
    );
    if estimate.seconds > REFUSE_SECONDS || memory.is_some_and(|m| estimate.bytes > m) {
        let machine = memory.map_or(String::new(), |m| {
            format!(", this machine has {}", human_bytes(m))
        });
        return Err(usage(format!(
            "{numbers} (limits: {}{machine}); lower --size, --spp or --light-samples",
            duration(REFUSE_SECONDS)
        )));
    }
    if !yes && (estimate.seconds > CONFIRM_SECONDS || estimate.bytes > CONFIRM_BYTES) {
        return Err(usage(format!(
            "{numbers}, above the {} / {} that run without asking; add --yes to go ahead",
            duration(CONFIRM_SECONDS),
            human_bytes(CONFIRM_BYTES)
        )));
    }
    Ok(())
}

/// The image size against the device's largest texture, its largest
/// buffer (the readback) and the GPU memory budget.
pub fn check_gpu(limits: &wgpu::Limits, adapter: &str, (width, height): (u32, u32)) -> anyhow::Result<()> {
    let side = limits.max_texture_dimension_2d;
    if width > side || height > side {
        return Err(usage(format!(
            "--size {width}x{height}: larger than the {side} texels a side this GPU allows ({adapter})"
        )));
    }
    let pixels = width as u64 * height as u64;
    let row = (16 * width as u64).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT as u64);
    let readback = row * height as u64;
    if readback > limits.max_buffer_size {
        return Err(usage(format!(
            "--size {width}x{height}: reading the image back takes {}, more than the {} this GPU allows in one buffer",
            human_bytes(readback),
            human_bytes(limits.max_buffer_size)
        )));
    }
    let bytes = pixels * GPU_BYTES_PER_PIXEL;
    if bytes > GPU_IMAGE_BUDGET_BYTES {
        return Err(usage(format!(
            "--size {width}x{height}: the GPU images would take about {}, above the {} budget",
            human_bytes(bytes),
            human_bytes(GPU_IMAGE_BUDGET_BYTES)
        )));
    }
    Ok(())
}

/// MemTotal of /proc/meminfo, where there is one.
fn physical_memory_bytes() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemTotal:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// 42 s, 12 min, 3.5 h, 20 days.
fn duration(seconds: f64) -> String {
    match seconds {
        s if s < 60.0 => format!("{s:.0} s"),
        s if s < 3600.0 => format!("{:.0} min", s / 60.0),
        s if s < 48.0 * 3600.0 => format!("{:.1} h", s / 3600.0),
        s => format!("{:.0} days", s / 86400.0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cheap_work_runs_dear_work_asks_absurd_work_is_refused() {
        let cheap = Estimate {
            seconds: 1.0,
            bytes: 1 << 20,
        };
        assert!(check_cpu("x", cheap, false).is_ok());
        let dear = Estimate {
            seconds: 3600.0,
            bytes: 1 << 20,
        };
        let asked = check_cpu("the reference", dear, false).unwrap_err().to_string();
        assert!(asked.contains("--yes") && asked.contains("1.0 h"), "{asked}");
        assert!(check_cpu("x", dear, true).is_ok());
        let absurd = Estimate {
            seconds: 1e9,
            bytes: 1 << 20,
        };
        assert!(
            check_cpu("x", absurd, true)
                .unwrap_err()
                .to_string()
                .contains("days")
        );
    }

    #[test]
    fn reference_cost_grows_with_every_sample() {
        let mut settings = Settings::default();
        settings.light.radius_m = 0.5;
        let options = ReferenceOptions {
            spp: 4,
            light_samples: 64,
            ..ReferenceOptions::DEFAULT
        };
        let base = reference(&settings, &options, 0);
        let more = reference(&settings, &ReferenceOptions { spp: 8, ..options }, 0);
        assert!((more.seconds / base.seconds - 2.0).abs() < 1e-9);
        settings.image.width = 16384;
        settings.image.height = 16384;
        let huge = reference(
            &settings,
            &ReferenceOptions {
                spp: 65536,
                ..options
            },
            0,
        );
        assert!(check_cpu("x", huge, true).is_err());
    }

    #[test]
    fn sizes_beyond_the_device_are_refused() {
        let limits = wgpu::Limits::default();
        assert!(check_gpu(&limits, "test", (1280, 720)).is_ok());
        let side = limits.max_texture_dimension_2d + 1;
        assert!(
            check_gpu(&limits, "test", (side, 16))
                .unwrap_err()
                .to_string()
                .contains("texels a side")
        );
    }
}
