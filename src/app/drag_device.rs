//! Drag frames rendered on a device and a thread of their own.
//!
//! A software adapter (lavapipe, llvmpipe) executes a submission on the
//! thread that submits it: rendering the view on the window's device keeps
//! the UI thread waiting for it (~15 ms of a ~30 ms drag frame), then the
//! window's paint and present wait for the UI thread. With a second device
//! (the same adapter from an instance of its own, see [`same_adapter_anew`]),
//! the view renders on a worker thread while the UI thread lays out, paints
//! and presents the last finished image: a drag frame costs the longer of
//! the two instead of their sum. The worker's image comes back as bytes (a
//! reduced drag image is ~0.1–0.7 MB) and is copied into the texture the
//! window shows.
//!
//! Only drag frames go there: full frames, the probe's and the error
//! statistics' readbacks stay on the window's device. A frame that arrives
//! after its drag ended is dropped. The worker keeps its own copy of the
//! scene's GPU buffers (uploaded when the scene changes, and a large
//! scene's simplified meshes once they are built) and compiles the
//! next drag's pipeline ahead after each full frame, as the window's
//! renderer did before.

use crate::gpu::raytrace::Accumulation;
use crate::gpu::timing::PassTimes;
use crate::gpu::{ComparisonImage, FrameReport, Renderer, ShadeOptions};
use crate::presets::Half;
use crate::scene::Scene;
use crate::scene::simplify::SimplifiedMeshes;
use crate::settings::Settings;
use std::sync::Arc;
use std::sync::mpsc::{Receiver, Sender, channel};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

crate::named_enum! {
    /// Where drag frames render (`--drag-device`).
    #[derive(Default)]
    pub enum DragDevice {
        /// A device of their own on software adapters (where a submission
        /// runs on the submitting thread), the window's on GPUs.
        #[default]
        Auto = "auto",
        /// The window's device, on the UI thread.
        Same = "same",
        /// A device of their own, whatever the adapter.
        Own = "own",
    }
}

impl DragDevice {
    /// Whether drag frames get a device of their own on `adapter`.
    pub fn own_on(self, adapter: &wgpu::Adapter) -> bool {
        match self {
            Self::Auto => adapter.get_info().device_type == wgpu::DeviceType::Cpu,
            Self::Same => false,
            Self::Own => true,
        }
    }
}

/// A drag frame to render; `tag` comes back with its image.
pub struct Job<T> {
    pub half: Half,
    pub settings: Settings,
    pub size: (u32, u32),
    pub tag: T,
}

/// A finished drag frame.
pub struct DragFrame<T> {
    pub half: Half,
    /// The settings it was drawn with (the job's).
    pub settings: Settings,
    /// sRGB-encoded RGBA bytes, row-major from the top.
    pub image: image::RgbaImage,
    pub report: FrameReport,
    /// GPU time of each pass (None without timestamp queries).
    pub times: Option<PassTimes>,
    /// CPU time of the render call (encoding and submitting, ms).
    pub render_cpu_ms: f64,
    /// The false-colour scale, for the views that scale to the image.
    pub scale: Option<f32>,
    /// Its ray-traced accumulation (None: V from the shadow map).
    pub accumulation: Option<Accumulation>,
    pub tag: T,
}

enum Message<T> {
    Scene(Arc<Scene>),
    /// The current scene's simplified meshes, which drag frames draw.
    Simplified(Arc<SimplifiedMeshes>),
    Split(bool),
    Comparison(Half, Option<Arc<ComparisonImage>>),
    /// Compile the pipeline a drag from these settings will need.
    CompileAhead(Half, Settings),
    Render(Job<T>, egui::Context),
}

/// The worker and the frames it sent back, one slot per half.
pub struct DragRenderer<T> {
    /// None once dropped: the worker's inbox closes and it ends.
    jobs: Option<Sender<Message<T>>>,
    worker: Option<JoinHandle<()>>,
    frames: Receiver<DragFrame<T>>,
    /// A job sent and its frame not yet back, per half.
    busy: [bool; 2],
    ready: [Option<DragFrame<T>>; 2],
}

impl<T: Send + 'static> DragRenderer<T> {
    /// A worker on a new device of `adapter`, with `scene` uploaded on its
    /// thread; None when the device cannot be created (drag frames then
    /// render on the window's device).
    pub fn new(adapter: &wgpu::Adapter, scene: Arc<Scene>) -> Option<Self> {
        let adapter = same_adapter_anew(adapter).unwrap_or_else(|| adapter.clone());
        let descriptor = crate::gpu::context::device_descriptor(&adapter);
        let (device, queue) = pollster::block_on(adapter.request_device(&descriptor)).ok()?;
        let (jobs, inbox) = channel();
        let (outbox, frames) = channel();
        let worker = std::thread::Builder::new()
            .name("lumlab drag device".into())
            .spawn(move || {
                let renderer = Renderer::new(&adapter, &device, &queue, &scene);
                Worker {
                    halves: [Some(renderer), None],
                }
                .run(&inbox, &outbox);
            })
            .ok()?;
        Some(Self {
            jobs: Some(jobs),
            worker: Some(worker),
            frames,
            busy: [false; 2],
            ready: [None, None],
        })
    }

    /// Sends a message to the worker; false when it is gone.
    fn send(&self, message: Message<T>) -> bool {
        self.jobs.as_ref().is_some_and(|jobs| jobs.send(message).is_ok())
    }

    pub fn set_scene(&self, scene: Arc<Scene>) {
        self.send(Message::Scene(scene));
    }

    pub fn set_simplified(&self, meshes: Arc<SimplifiedMeshes>) {
        self.send(Message::Simplified(meshes));
    }

    pub fn set_split(&self, on: bool) {
        self.send(Message::Split(on));
    }

    pub fn set_comparison(&self, half: Half, image: Option<Arc<ComparisonImage>>) {
        self.send(Message::Comparison(half, image));
    }

    pub fn compile_ahead(&self, half: Half, settings: Settings) {
        self.send(Message::CompileAhead(half, settings));
    }

    /// Whether a half's job is on its way (its frame not yet taken): the
    /// next is sent once it is back, so the worker never runs behind.
    pub fn busy(&self, half: Half) -> bool {
        self.busy[half as usize]
    }

    /// Whether the worker ended (it failed): drag frames then render on
    /// the window's device.
    pub fn is_gone(&self) -> bool {
        self.worker.as_ref().is_none_or(JoinHandle::is_finished)
    }

    /// Sends a job for a half that is not busy; `wake` is asked to repaint
    /// when its frame is back.
    pub fn render(&mut self, job: Job<T>, wake: egui::Context) {
        let half = job.half as usize;
        self.busy[half] = self.send(Message::Render(job, wake));
    }

    /// A half's finished frame, if one came back since the last call or
    /// comes back within `wait` (none while the half is not busy).
    pub fn take(&mut self, half: Half, wait: Duration) -> Option<DragFrame<T>> {
        while let Ok(frame) = self.frames.try_recv() {
            self.keep(frame);
        }
        let deadline = Instant::now() + wait;
        while self.ready[half as usize].is_none() && self.busy[half as usize] {
            let left = deadline.saturating_duration_since(Instant::now());
            match self.frames.recv_timeout(left) {
                Ok(frame) => self.keep(frame),
                Err(_) => break,
            }
        }
        self.ready[half as usize].take()
    }

    fn keep(&mut self, frame: DragFrame<T>) {
        let i = frame.half as usize;
        self.busy[i] = false;
        self.ready[i] = Some(frame);
    }
}

impl<T> Drop for DragRenderer<T> {
    /// Ends the worker and waits for it: its device must not outlive the
    /// window (the process would end with the driver's threads busy).
    fn drop(&mut self) {
        self.jobs = None;
        if let Some(worker) = self.worker.take() {
            let _ = worker.join();
        }
    }
}

/// `adapter` as a new instance enumerates it, if it does. lavapipe
/// rasterizes for all the devices of one instance's adapter on one pool of
/// threads (perf over a drag: two rasterizer threads busy, the other pool
/// idle): from an instance of its own, the drag device has its own pool,
/// and the view's image does not queue behind the window's paint.
fn same_adapter_anew(adapter: &wgpu::Adapter) -> Option<wgpu::Adapter> {
    let wanted = adapter.get_info();
    let instance = crate::gpu::context::instance();
    pollster::block_on(instance.enumerate_adapters(wanted.backend.into()))
        .into_iter()
        .find(|a| a.get_info() == wanted)
}

/// The worker thread's renderers, one per half as on the window's device
/// (B shares A's scene and shadow maps).
struct Worker {
    halves: [Option<Renderer>; 2],
}

impl Worker {
    fn run<T>(mut self, inbox: &Receiver<Message<T>>, outbox: &Sender<DragFrame<T>>) {
        for half in self.halves.iter_mut().flatten() {
            half.set_shade_options(ShadeOptions::INTERACTION);
        }
        while let Ok(message) = inbox.recv() {
            let Message::Render(job, wake) = message else {
                self.apply(message);
                continue;
            };
            // The split's message comes before B's first job; should it
            // not, B is made here: every job gets its frame back.
            if job.half == Half::B {
                self.set_split(true);
            }
            let Some(renderer) = &mut self.halves[job.half as usize] else {
                continue;
            };
            if outbox.send(render(renderer, job)).is_err() {
                return;
            }
            wake.request_repaint();
        }
    }

    /// A message other than a job.
    fn apply<T>(&mut self, message: Message<T>) {
        match message {
            Message::Scene(scene) => {
                if let Some(a) = &mut self.halves[Half::A as usize] {
                    a.set_scene(&scene);
                }
            }
            Message::Simplified(meshes) => {
                if let Some(a) = &mut self.halves[Half::A as usize] {
                    a.set_simplified(&meshes);
                }
            }
            Message::Split(on) => self.set_split(on),
            Message::Comparison(half, image) => {
                if let Some(h) = &mut self.halves[half as usize] {
                    h.set_comparison(image.map(|i| (*i).clone()));
                }
            }
            Message::CompileAhead(half, settings) => {
                if let Some(h) = &mut self.halves[half as usize] {
                    h.compile_ahead(&settings, ShadeOptions::INTERACTION);
                }
            }
            Message::Render(..) => {}
        }
    }

    fn set_split(&mut self, on: bool) {
        let [a, b] = &mut self.halves;
        match (on, b.is_some()) {
            (true, false) => {
                if let Some(a) = a {
                    let mut shared = a.sharing();
                    shared.set_shade_options(ShadeOptions::INTERACTION);
                    *b = Some(shared);
                }
            }
            (false, true) => *b = None,
            _ => {}
        }
    }
}

/// Renders a job and reads its image back (waiting for the device: this
/// thread has nothing else to do).
fn render<T>(renderer: &mut Renderer, job: Job<T>) -> DragFrame<T> {
    let start = Instant::now();
    let report = renderer.render(&job.settings, job.size);
    let render_cpu_ms = start.elapsed().as_secs_f64() * 1e3;
    let image = renderer.read_display();
    let scale = crate::gpu::display::scales_to_image(job.settings.view.mode).then(|| renderer.read_scale());
    DragFrame {
        half: job.half,
        settings: job.settings,
        image,
        report,
        times: renderer.wait_timings(),
        render_cpu_ms,
        scale,
        accumulation: renderer.accumulation(),
        tag: job.tag,
    }
}
