//! When the full meshes' BVH is built. Nothing builds it at a scene's
//! upload: a frame under the shadow map never reads it, and on a 110 k-
//! triangle model the build was a fifth of a whole `lumlab render`'s
//! instructions. The command line builds it on the first frame that traces
//! rays; the app also starts it on a thread of its own once a scene is
//! uploaded ([`BvhBuild::start_in_background`]), and uploads it there too:
//! a first ray-traced frame of a large model then waits for what is left of
//! the build, if anything, not for all of it. On the 2-core AMD host, three
//! runs a scene, the first ray-traced frame's wait 3 s after the upload:
//! the 1 M-triangle race scene 0.77–0.86 s without it, 0.11–0.13 s with the
//! build alone in the background, 2.6–3.3 ms with the upload there too; the
//! engine model 0.09–0.12 s, 13–17 ms, under 0.1 ms.

use super::bvh::{FlatBvh, GpuBvh};
use glam::Vec3;
use std::sync::{Arc, Mutex, MutexGuard};
use std::thread::JoinHandle;

/// The casters' triangles until their BVH is taken.
pub struct BvhBuild(Mutex<State>);

enum State {
    /// Not started: built by the first frame that traces rays.
    Waiting(Vec<[Vec3; 3]>),
    /// On its thread. The triangles stay shared with it, so that a build
    /// whose thread fails can be run again here.
    Building(Arc<Vec<[Vec3; 3]>>, JoinHandle<GpuBvh>),
    /// Handed over by [`BvhBuild::take`].
    Taken,
}

impl BvhBuild {
    /// The corners of the triangles that cast shadows.
    pub fn new(triangles: Vec<[Vec3; 3]>) -> Self {
        Self(Mutex::new(State::Waiting(triangles)))
    }

    /// Starts the build and its upload to `device` on a thread of its own,
    /// unless it is started or taken already; where no thread can be
    /// started, the first frame that traces rays still builds it.
    pub fn start_in_background(&self, device: &wgpu::Device) {
        let mut state = self.lock();
        let State::Waiting(triangles) = &mut *state else {
            return;
        };
        let triangles = Arc::new(std::mem::take(triangles));
        let (shared, device) = (Arc::clone(&triangles), device.clone());
        let spawned = std::thread::Builder::new()
            .name("lumlab bvh".into())
            .spawn(move || GpuBvh::new(&device, &FlatBvh::new(&shared)));
        *state = match spawned {
            Ok(thread) => State::Building(triangles, thread),
            Err(_) => State::Waiting(Arc::unwrap_or_clone(triangles)),
        };
    }

    /// The BVH on `device`, once: built here when `needed` and not
    /// started, waited for when `needed` and on its way, handed over
    /// without waiting when its thread is done. None while it is not needed
    /// and not ready, and after it was taken.
    pub fn take(&self, device: &wgpu::Device, needed: bool) -> Option<GpuBvh> {
        let mut state = self.lock();
        let ready = match &*state {
            State::Waiting(_) => needed,
            State::Building(_, thread) => needed || thread.is_finished(),
            State::Taken => false,
        };
        if !ready {
            return None;
        }
        let build = |triangles: &[[Vec3; 3]]| GpuBvh::new(device, &FlatBvh::new(triangles));
        match std::mem::replace(&mut *state, State::Taken) {
            State::Waiting(triangles) => Some(build(&triangles)),
            State::Building(triangles, thread) => Some(thread.join().unwrap_or_else(|_| build(&triangles))),
            State::Taken => None,
        }
    }

    fn lock(&self) -> MutexGuard<'_, State> {
        self.0.lock().unwrap_or_else(|e| e.into_inner())
    }
}
