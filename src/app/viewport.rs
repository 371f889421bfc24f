//! The central viewport: the renderer's image (one texture per half of the
//! split view), camera orbit/pan/zoom, the light gizmo, the split divider,
//! the probe's marker, the half labels and the colour legends.

use super::camera_control::{drag_height, drag_in_image_plane, orbit, pan, project, zoom};
use super::gpu_view::GpuViews;
use super::legend;
use super::probe::ProbePixel;
use super::state::{SplitLayout, SplitState};
use crate::presets::Half;
use crate::scene::SceneScale;
use crate::settings::{DebugView, Settings};
use crate::tr;
use egui::emath::GuiRounding;
use egui::{Align2, Color32, CursorIcon, FontId, PointerButton, Pos2, Rect, Sense, Stroke, Vec2};
use glam::DVec2;

/// Degrees of orbit per point dragged.
const ORBIT_DEG_PER_POINT: f64 = 0.3;
/// Zoom factor per point of scroll: e^(−scroll · k).
const ZOOM_PER_POINT: f64 = 0.0015;
/// Radius of the light gizmo (points).
const GIZMO_RADIUS: f32 = 11.0;
/// The gap between the two images side by side (points).
const SIDE_BY_SIDE_GAP: f32 = 6.0;
const LIGHT_YELLOW: Color32 = Color32::from_rgb(255, 214, 60);
/// How soon a frame follows one shown at a reduced render scale.
const PREVIEW_REPAINT: std::time::Duration = std::time::Duration::from_millis(50);

pub struct Viewport<'a> {
    pub settings: &'a mut Settings,
    pub split: &'a mut SplitState,
    pub gpu: Option<&'a mut GpuViews>,
    pub probe: Option<ProbePixel>,
    /// A line to show over the image (e.g. the error view has no reference).
    pub banner: Option<String>,
    /// A number to show over the image, above the legend (e.g. the RMSE).
    pub caption: Option<String>,
    /// The scene's scale: the orbit's distance limits follow it.
    pub scale: SceneScale,
}

#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ViewportResponse {
    /// The image size in pixels (0 × 0 when there is no room).
    pub size: (u32, u32),
    /// Where the image is in the window (points); None when there is no room.
    pub rect: Option<egui::Rect>,
    /// A pixel clicked this frame.
    pub clicked: Option<ProbePixel>,
    /// A pixel double-clicked this frame (the orbit's new pivot).
    pub double_clicked: Option<ProbePixel>,
    /// Which halves were rendered this frame.
    pub rendered: [bool; 2],
    /// The camera, light or divider is being dragged.
    pub dragging: bool,
    /// The image shown is an interaction frame at a reduced render scale:
    /// nothing should be read back from it.
    pub preview: bool,
}

impl Viewport<'_> {
    /// The settings a half shows.
    pub fn settings_for(settings: &Settings, split: &SplitState, half: Half) -> Settings {
        if split.enabled {
            split.comparison.settings_for(half, settings)
        } else {
            settings.clone()
        }
    }

    /// What a half renders in a viewport of `size` pixels: its settings at
    /// that image size, with the camera widened to the viewport's shape
    /// (see [`crate::scene::Camera::widened_for`]). The renderer, the probe
    /// and the reference all use it: it is the one place the app decides
    /// which camera an image is seen from.
    pub fn render_settings(
        settings: &Settings,
        split: &SplitState,
        half: Half,
        size: (u32, u32),
    ) -> Settings {
        let mut s = Self::settings_for(settings, split, half);
        s.camera = s.camera.widened_for(size);
        s.image.width = size.0;
        s.image.height = size.1;
        s
    }

    pub fn show(self, ui: &mut egui::Ui) -> ViewportResponse {
        let Self {
            settings,
            split,
            gpu,
            probe,
            banner,
            caption,
            scale,
        } = self;
        let ppp = ui.ctx().pixels_per_point();
        let full = ui.available_rect_before_wrap().round_to_pixels(ppp);
        // Side by side, A's image is the left half and B's the right: each
        // a whole image of the same view. `rect` is A's (or the only) image.
        let side_by_side = split.enabled && split.layout == SplitLayout::SideBySide;
        let (rect, rect_b) = if side_by_side {
            let gap = SIDE_BY_SIDE_GAP / 2.0;
            let mid = full.center().x;
            (
                Rect::from_min_max(full.min, Pos2::new(mid - gap, full.max.y)).round_to_pixels(ppp),
                Rect::from_min_max(Pos2::new(mid + gap, full.min.y), full.max).round_to_pixels(ppp),
            )
        } else {
            (full, full)
        };
        let size = (
            (rect.width() * ppp).round().max(0.0) as u32,
            (rect.height() * ppp).round().max(0.0) as u32,
        );
        let mut out = ViewportResponse::default();
        if size.0 < 2 || size.1 < 2 {
            // Minimized or squeezed: nothing to draw, nothing to render.
            return out;
        }
        out.size = size;
        out.rect = Some(rect);
        let response = ui.allocate_rect(full, Sense::click_and_drag());
        let height_px = size.1 as f64;
        let wipe_x = rect.min.x + rect.width() * split.wipe.clamp(0.0, 1.0);

        // The light gizmo and the divider are on top of the image: they take
        // the drag when the pointer is on them.
        let aspect_size = (size.0 as f64, size.1 as f64);
        // The camera as this viewport shows it: projections and drags use it.
        let view_camera = settings.camera.widened_for(size);
        let light_px = project(&view_camera, settings.light.position, aspect_size);
        let to_points = |p: DVec2| rect.min + Vec2::new(p.x as f32, p.y as f32) / ppp;
        // Off-image, the gizmo waits at the edge, pointing to the light.
        // The top band is left to the half labels.
        let mut inner = rect.shrink(GIZMO_RADIUS + 14.0);
        inner.min.y = (rect.min.y + 64.0).min(inner.max.y);
        let gizmo_at = light_px.map(to_points).map(|p| {
            if inner.contains(p) {
                (p, None)
            } else {
                (inner.clamp(p), Some(p))
            }
        });
        let mut dragging_other = false;
        if let Some((p, _)) = gizmo_at {
            let gizmo = ui
                .interact(
                    Rect::from_center_size(p, Vec2::splat(2.0 * GIZMO_RADIUS + 6.0)),
                    gizmo_id(),
                    Sense::drag(),
                )
                .on_hover_text(tr!(
                    "viewport-gizmo-tip",
                    x = format!("{:.2}", settings.light.position.x),
                    y = format!("{:.2}", settings.light.position.y),
                    z = format!("{:.2}", settings.light.position.z)
                ));
            if gizmo.hovered() || gizmo.dragged() {
                ui.ctx().set_cursor_icon(CursorIcon::Grab);
            }
            if gizmo.dragged() {
                dragging_other = true;
                let delta = gizmo.drag_delta() * ppp;
                let light = &mut settings.light.position;
                *light = if ui.input(|i| i.modifiers.command || i.modifiers.ctrl) {
                    drag_height(&view_camera, *light, delta.y as f64, height_px)
                } else {
                    drag_in_image_plane(
                        &view_camera,
                        *light,
                        DVec2::new(delta.x as f64, delta.y as f64),
                        height_px,
                    )
                };
            }
        }
        if split.enabled && !side_by_side {
            let divider = ui
                .interact(
                    Rect::from_center_size(
                        Pos2::new(wipe_x, rect.center().y),
                        Vec2::new(12.0, rect.height()),
                    ),
                    ui.make_persistent_id("split divider"),
                    Sense::drag(),
                )
                .on_hover_text(tr!("viewport-divider-tip"));
            if divider.hovered() || divider.dragged() {
                ui.ctx().set_cursor_icon(CursorIcon::ResizeHorizontal);
            }
            if divider.dragged() {
                dragging_other = true;
                split.wipe = (split.wipe + divider.drag_delta().x / rect.width()).clamp(0.0, 1.0);
            }
        }

        // Camera: orbit with the left button, pan with shift or the middle button, zoom with the wheel.
        if !dragging_other && response.dragged() {
            let delta = response.drag_delta();
            let shift = ui.input(|i| i.modifiers.shift);
            if response.dragged_by(PointerButton::Middle)
                || (shift && response.dragged_by(PointerButton::Primary))
            {
                let mut moved = view_camera;
                pan(
                    &mut moved,
                    DVec2::new(delta.x as f64, delta.y as f64) * ppp as f64,
                    height_px,
                );
                settings.camera.eye = moved.eye;
                settings.camera.target = moved.target;
                ui.ctx().set_cursor_icon(CursorIcon::Move);
            } else if response.dragged_by(PointerButton::Primary) {
                orbit(
                    &mut settings.camera,
                    -delta.x as f64 * ORBIT_DEG_PER_POINT,
                    delta.y as f64 * ORBIT_DEG_PER_POINT,
                );
                ui.ctx().set_cursor_icon(CursorIcon::Grabbing);
            }
        }
        out.dragging = dragging_other || response.dragged();
        if response.hovered() {
            let scroll = ui.input(|i| i.smooth_scroll_delta.y) as f64;
            if scroll != 0.0 {
                zoom(
                    &mut settings.camera,
                    (-scroll * ZOOM_PER_POINT).exp(),
                    scale.orbit_distance_m(),
                );
            }
        }
        let wipe_x = rect.min.x + rect.width() * split.wipe.clamp(0.0, 1.0);
        let pixel_at = |pos: Pos2| {
            let half = if split.enabled && pos.x >= if side_by_side { rect_b.min.x } else { wipe_x } {
                Half::B
            } else {
                Half::A
            };
            let origin = if side_by_side && half == Half::B {
                rect_b.min
            } else {
                rect.min
            };
            let local = (pos - origin) * ppp;
            let pixel = (
                (local.x.max(0.0) as u32).min(size.0 - 1),
                (local.y.max(0.0) as u32).min(size.1 - 1),
            );
            ProbePixel { half, pixel, size }
        };
        if let Some(pos) = response.interact_pointer_pos() {
            if response.double_clicked() {
                out.double_clicked = Some(pixel_at(pos));
            } else if response.clicked() {
                out.clicked = Some(pixel_at(pos));
            }
        }

        // Render (only what changed) and show.
        let painter = ui.painter_at(full);
        let halves: &[Half] = if split.enabled {
            &[Half::A, Half::B]
        } else {
            &[Half::A]
        };
        let Some(gpu) = gpu else {
            painter.text(
                rect.center(),
                Align2::CENTER_CENTER,
                tr!("viewport-no-gpu"),
                FontId::proportional(20.0),
                Color32::WHITE,
            );
            return out;
        };
        // While anything is dragged (here or a slider in a panel) the image
        // is rendered at a reduced scale; the first frame after is full size.
        let interacting = out.dragging || ui.ctx().dragged_id().is_some();
        let scale = gpu.begin_frame(interacting);
        let render_size = if scale < 1.0 {
            let side = |n: u32| ((n as f64 * scale).round() as u32).max(1);
            (side(size.0), side(size.1))
        } else {
            size
        };
        for &half in halves {
            let s = Self::render_settings(settings, split, half, render_size);
            // The probe reads V and the texel density from the aux target.
            let probed = [probe, out.clicked].iter().flatten().any(|p| p.half == half);
            out.rendered[half as usize] = gpu.prepare(half, &s, render_size, probed, ui.ctx());
        }
        out.preview = gpu.rendered_scale(Half::A) < 1.0;
        if out.preview {
            // Should the drag's end come without an event of its own, this
            // repaint still brings the full-resolution frame.
            ui.ctx().request_repaint_after(PREVIEW_REPAINT);
        }
        let whole = Rect::from_min_max(Pos2::ZERO, Pos2::new(1.0, 1.0));
        let part = |half: Half| -> (Rect, Rect) {
            let t = split.wipe.clamp(0.0, 1.0);
            match (split.enabled, half) {
                (false, _) => (rect, whole),
                (true, Half::A) if side_by_side => (rect, whole),
                (true, Half::B) if side_by_side => (rect_b, whole),
                (true, Half::A) => (
                    Rect::from_min_max(rect.min, Pos2::new(wipe_x, rect.max.y)),
                    Rect::from_min_max(Pos2::ZERO, Pos2::new(t, 1.0)),
                ),
                (true, Half::B) => (
                    Rect::from_min_max(Pos2::new(wipe_x, rect.min.y), rect.max),
                    Rect::from_min_max(Pos2::new(t, 0.0), Pos2::new(1.0, 1.0)),
                ),
            }
        };
        for &half in halves {
            let (area, uv) = part(half);
            if let Some(image) = gpu.image(half, area, uv) {
                painter.add(image);
            }
        }

        // Overlays: labels, divider, legends, light, probe, banner.
        let view = settings.view.mode;
        for &half in halves {
            let (area, _) = part(half);
            let Some(h) = gpu.half(half) else { continue };
            let compares = matches!(view, DebugView::Error | DebugView::RefVisibility);
            if compares && !h.has_comparison {
                continue;
            }
            if view == DebugView::DeltaE
                && Self::settings_for(settings, split, half)
                    .colour
                    .illuminant
                    .is_none()
            {
                legend::paint_note(&painter, area, &tr!("legend-delta-e-needs-illuminant"));
                continue;
            }
            if let Some(l) = legend::for_view(view, h.scale) {
                legend::paint(&painter, area, &l);
            }
        }
        for &half in halves {
            if let Some(a) = gpu.accumulation(half) {
                let (area, _) = part(half);
                let target = Self::settings_for(settings, split, half)
                    .shadow
                    .rt_noise_target_percent;
                let elapsed = gpu.accumulation_elapsed(half);
                super::visibility::paint_accumulation(&painter, area, &a, target, elapsed);
            }
            if gpu.accumulating(half) {
                ui.ctx().request_repaint();
            }
        }
        if split.enabled {
            let labels = if side_by_side {
                [
                    (Half::A, Align2::LEFT_TOP, rect.min.x + 10.0),
                    (Half::B, Align2::LEFT_TOP, rect_b.min.x + 10.0),
                ]
            } else {
                painter.line_segment(
                    [Pos2::new(wipe_x, rect.min.y), Pos2::new(wipe_x, rect.max.y)],
                    Stroke::new(3.0, Color32::WHITE),
                );
                [
                    (Half::A, Align2::RIGHT_TOP, wipe_x - 10.0),
                    (Half::B, Align2::LEFT_TOP, wipe_x + 10.0),
                ]
            };
            for (half, align, x) in labels {
                let name = if half == Half::A { "A" } else { "B" };
                label(
                    ui,
                    Pos2::new(x, rect.min.y + 10.0),
                    align,
                    &format!(
                        "{name}: {}",
                        super::names::comparison_label(&split.comparison, half)
                    ),
                );
            }
        }
        match gizmo_at {
            Some((p, None)) => {
                sun(&painter, p);
                // A drop line to the ground plane y = 0 shows the light's height.
                let foot = glam::Vec3::new(settings.light.position.x, 0.0, settings.light.position.z);
                if let Some(f) = project(&view_camera, foot, aspect_size).map(to_points) {
                    let stroke = Stroke::new(1.5, LIGHT_YELLOW.gamma_multiply(0.7));
                    painter.line_segment([p, f], stroke);
                    painter.circle_stroke(f, 4.0, stroke);
                }
            }
            Some((p, Some(target))) => {
                sun(&painter, p);
                let dir = (target - p).normalized();
                painter.arrow(
                    p + dir * (GIZMO_RADIUS + 2.0),
                    dir * 22.0,
                    Stroke::new(3.0, LIGHT_YELLOW),
                );
                // The label goes towards the middle of the image, where there is room.
                let towards_left = p.x > rect.center().x;
                let side = if towards_left {
                    Align2::RIGHT_CENTER
                } else {
                    Align2::LEFT_CENTER
                };
                let offset = if towards_left { -1.0 } else { 1.0 } * (GIZMO_RADIUS + 14.0);
                label(
                    ui,
                    p + Vec2::new(offset, 0.0),
                    side,
                    &tr!("viewport-light-off-image"),
                );
            }
            None => label(
                ui,
                rect.right_top() + Vec2::new(-10.0, 44.0),
                Align2::RIGHT_TOP,
                &tr!("viewport-light-behind"),
            ),
        }
        if let Some(probe) = probe
            && probe.size == size
        {
            let origin = if side_by_side && probe.half == Half::B {
                rect_b.min
            } else {
                rect.min
            };
            let p = origin + Vec2::new(probe.pixel.0 as f32 + 0.5, probe.pixel.1 as f32 + 0.5) / ppp;
            painter.circle_stroke(p, 7.0, Stroke::new(2.0, Color32::BLACK));
            painter.circle_stroke(p, 6.0, Stroke::new(2.0, Color32::from_rgb(0, 230, 255)));
        }
        if let Some(text) = banner {
            label(ui, full.center(), Align2::CENTER_CENTER, &text);
        }
        if let Some(text) = caption {
            label(
                ui,
                Pos2::new(full.center().x, full.max.y - 104.0),
                Align2::CENTER_BOTTOM,
                &text,
            );
        }
        out
    }
}

/// The light gizmo's widget: one per window, so a fixed id, by which
/// `lumlab --drag-bench-target light` finds where to press.
pub(super) fn gizmo_id() -> egui::Id {
    egui::Id::unique("lumlab light gizmo")
}

/// The light gizmo: a small sun.
fn sun(painter: &egui::Painter, p: Pos2) {
    painter.circle(p, GIZMO_RADIUS, LIGHT_YELLOW, Stroke::new(2.0, Color32::BLACK));
    for k in 0..8 {
        let a = k as f32 * std::f32::consts::FRAC_PI_4;
        let d = Vec2::new(a.cos(), a.sin());
        painter.line_segment(
            [p + d * (GIZMO_RADIUS + 3.0), p + d * (GIZMO_RADIUS + 8.0)],
            Stroke::new(2.0, LIGHT_YELLOW),
        );
    }
}

/// Large white text on a dark pill, readable over any image; a real label
/// (not only paint), so screen readers and tests find it.
fn label(ui: &mut egui::Ui, pos: Pos2, align: Align2, text: &str) {
    let font = FontId::proportional(19.0);
    let galley = ui
        .painter()
        .layout_no_wrap(text.to_string(), font.clone(), Color32::WHITE);
    let rect = align.anchor_size(pos, galley.size());
    ui.painter().rect_filled(
        rect.expand2(Vec2::new(8.0, 4.0)),
        6.0,
        Color32::from_black_alpha(170),
    );
    ui.put(
        rect,
        egui::Label::new(egui::RichText::new(text).font(font).color(Color32::WHITE))
            .selectable(false)
            .extend(),
    );
}
