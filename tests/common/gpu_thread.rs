//! One thread per test binary that does all its GPU work, with one device:
//! the test threads never touch the driver.
//!
//! Each test on a thread of its own with a device of its own hung
//! `tests/reference_gpu.rs` on an NVIDIA H200 in 7 of 14 runs, every test
//! thread parked on a futex; with `--test-threads=1` (every test on the
//! harness's one thread) it passed every run. Another project saw NVIDIA's
//! driver stall threads that had touched it when many exit at once
//! (docs/performance.md, "On a real GPU"). Here only this thread touches
//! the GPU, as with `--test-threads=1`, and it lives as long as the
//! process, while the tests' CPU work (the reference) still runs in
//! parallel.

use lumlab::gpu::{FrameReport, GpuContext};
use lumlab::scene::Scene;
use lumlab::settings::Settings;
use std::panic::{self, AssertUnwindSafe};
use std::sync::OnceLock;
use std::sync::mpsc::{self, Sender};
use std::thread;

/// A job given the GPU, or why there is none.
type Job = Box<dyn FnOnce(Result<&GpuContext, &str>) + Send>;

/// Runs `job` on the GPU thread with its device and returns what it
/// returns; a panic in `job` is the caller's, and no adapter is a failure
/// that says what to install, as `super::gpu` says it.
pub fn on_gpu_thread<R: Send + 'static>(job: impl FnOnce(&GpuContext) -> R + Send + 'static) -> R {
    let (answer, answered) = mpsc::channel();
    let job: Job = Box::new(move |gpu| {
        let result = gpu
            .map(|gpu| panic::catch_unwind(AssertUnwindSafe(|| job(gpu))))
            .map_err(str::to_owned);
        // The caller waits for this answer: it cannot be gone.
        let _ = answer.send(result);
    });
    gpu_thread()
        .send(job)
        .expect("the GPU thread lives as long as the process");
    match answered.recv().expect("the GPU thread answers every job") {
        Ok(Ok(value)) => value,
        Ok(Err(payload)) => panic::resume_unwind(payload),
        Err(e) => panic!("GPU test needs an adapter: {e}"),
    }
}

/// The GPU thread's queue, the thread started (and its device made) by
/// the first job.
fn gpu_thread() -> &'static Sender<Job> {
    static QUEUE: OnceLock<Sender<Job>> = OnceLock::new();
    QUEUE.get_or_init(|| {
        let (queue, jobs) = mpsc::channel::<Job>();
        thread::Builder::new()
            .name("gpu".into())
            .spawn(move || {
                let gpu = GpuContext::headless().map_err(|e| e.to_string());
                for job in jobs {
                    job(gpu.as_ref().map_err(String::as_str));
                }
            })
            .expect("a thread for the GPU");
        queue
    })
}

/// [`super::render`] on the GPU thread: one frame's report, quantity and
/// aux target.
pub fn render(scene: &Scene, settings: &Settings) -> (FrameReport, Vec<[f32; 4]>, Vec<[f32; 4]>) {
    let (scene, settings) = (scene.clone(), settings.clone());
    on_gpu_thread(move |gpu| super::render(gpu, &scene, &settings))
}
