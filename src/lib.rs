//! lumlab: a desktop lighting lab for direct lighting.
//!
//! `physics` holds the formulas (no GPU, no UI, no files); `settings` every
//! user-settable value; `scene` what is drawn; `cli` the command line;
//! `stability` the hard cases where direct lighting breaks numerically;
//! `app` the window (the only module that knows egui); `i18n` the language
//! of its text (French or English); `presets` the lecture's experiments; `tour` the lecture step by step.

#[macro_use]
mod named;

pub mod allocator;
pub mod app;
pub mod cli;
pub mod colour;
pub mod gpu;
pub mod i18n;
pub mod image_io;
pub mod input;
pub mod output;
pub mod physics;
pub mod plot;
pub mod presets;
pub mod reference;
pub mod report;
pub mod scene;
pub mod settings;
pub mod stability;
pub mod tour;
