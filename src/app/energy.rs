//! The energy panel: the directional albedo a(θ_i) of the current BRDF with
//! the region above 1 (energy created) shaded, the lecture's angles marked
//! and tabled; and a polar plot of the lobe in the plane of incidence.

use super::widgets::number;
use crate::physics::energy::{LECTURE_ANGLES_DEG, MAX_THETA_DEG, directional_albedo};
use crate::physics::{BrdfParams, Normalization, brdf};
use crate::tr;
use egui::{Color32, RichText};
use egui_plot::{Line, Plot, PlotPoints, Points, Span};
use glam::DVec3;

/// Points of the a(θ) curve.
const CURVE_POINTS: usize = 91;
/// The curves.
const CURVE: Color32 = Color32::from_rgb(90, 170, 255);
/// Red: energy is created.
const GAIN: Color32 = Color32::from_rgb(220, 60, 50);

/// The BRDF the panel shows (k, m, N of the current material settings).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnergyKey {
    pub k: f64,
    pub m: f64,
    pub norm: Normalization,
}

impl EnergyKey {
    fn params(&self) -> BrdfParams<f64> {
        BrdfParams {
            k: self.k,
            m: self.m,
            norm: self.norm,
        }
    }
}

/// a(θ) of one BRDF, computed once per change (about 10 ms).
struct Albedos {
    key: EnergyKey,
    /// (θ_i in degrees, a(θ_i)) along the curve.
    curve: Vec<[f64; 2]>,
    /// a(θ_i) at the lecture's angles.
    table: Vec<[f64; 2]>,
}

impl Albedos {
    fn new(key: EnergyKey) -> Self {
        let step = MAX_THETA_DEG / (CURVE_POINTS - 1) as f64;
        Self {
            key,
            curve: albedo_curve(&key, (0..CURVE_POINTS).map(|i| i as f64 * step)),
            table: albedo_curve(&key, LECTURE_ANGLES_DEG),
        }
    }
}

/// A BRDF to plot, with its name in the legend ("A: none").
pub struct Curve {
    pub name: String,
    pub key: EnergyKey,
}

#[derive(Default)]
pub struct EnergyPanel {
    /// The last curves computed (at most a few).
    cache: Vec<Albedos>,
}

/// Colours of the first and second curve (A and B of the split view).
const CURVES: [Color32; 2] = [CURVE, Color32::from_rgb(250, 150, 60)];

/// The albedo at the given angles.
pub fn albedo_curve(key: &EnergyKey, angles_deg: impl IntoIterator<Item = f64>) -> Vec<[f64; 2]> {
    let params = key.params();
    angles_deg
        .into_iter()
        .map(|theta| [theta, directional_albedo(theta, &params).value])
        .collect()
}

/// f_r / c (1/sr) for outgoing directions in the plane of incidence, as
/// polar points (f_r sin θ_o, f_r cos θ_o); θ_o < 0 lies on the light's
/// side. Extra samples around the mirror direction resolve sharp lobes.
pub fn lobe_polar(key: &EnergyKey, theta_i_deg: f64) -> Vec<[f64; 2]> {
    let theta_i = theta_i_deg.to_radians();
    let l = DVec3::new(-theta_i.sin(), theta_i.cos(), 0.0);
    let mirror = theta_i;
    let width = 1.0 / key.m.max(1.0).sqrt();
    let mut angles: Vec<f64> = (0..=360)
        .map(|i| (-89.75 + 179.5 * i as f64 / 360.0).to_radians())
        .collect();
    angles.extend((-48..=48).map(|i| mirror + i as f64 * 0.25 * width));
    angles.retain(|a| a.abs() < 89.9_f64.to_radians());
    angles.sort_by(f64::total_cmp);
    let params = key.params();
    angles
        .into_iter()
        .map(|a| {
            let o = DVec3::new(a.sin(), a.cos(), 0.0);
            let f = brdf::blinn_phong(DVec3::Y, l, o, &params).total();
            [f * a.sin(), f * a.cos()]
        })
        .collect()
}

impl EnergyPanel {
    /// The albedos of `key`, computed if not cached.
    fn albedos(&mut self, key: EnergyKey) -> usize {
        if let Some(i) = self.cache.iter().position(|a| a.key == key) {
            return i;
        }
        if self.cache.len() >= 4 {
            self.cache.remove(0);
        }
        self.cache.push(Albedos::new(key));
        self.cache.len() - 1
    }

    /// One curve, or two (A and B of a split view comparing normalizations);
    /// `theta_i_deg`: the light's incidence at the probed point or the scene centre.
    pub fn ui(&mut self, ui: &mut egui::Ui, curves: &[Curve], theta_i_deg: Option<(f64, &str)>) {
        let indices: Vec<usize> = curves.iter().map(|c| self.albedos(c.key)).collect();
        let data: Vec<(&Curve, &Albedos, Color32)> = curves
            .iter()
            .zip(&indices)
            .zip(CURVES)
            .map(|((c, &i), colour)| (c, &self.cache[i], colour))
            .collect();
        for (c, _, colour) in &data {
            let k = c.key;
            ui.label(
                RichText::new(format!(
                    "{}k = {}, m = {}, {}",
                    c.name,
                    number(k.k),
                    number(k.m),
                    k.norm.formula()
                ))
                .monospace()
                .color(*colour),
            )
            .on_hover_text(tr!("energy-curve-tip"));
        }
        let max_a = data
            .iter()
            .flat_map(|(_, a, _)| a.curve.iter().map(|p| p[1]))
            .fold(1.0_f64, f64::max);
        let top = (max_a * 1.1).max(1.2);
        Plot::new("albedo plot")
            .height(220.0)
            .allow_drag(false)
            .allow_zoom(false)
            .allow_scroll(false)
            .include_x(0.0)
            .include_x(90.0)
            .include_y(0.0)
            .include_y(top)
            .x_grid_spacer(egui_plot::uniform_grid_spacer(|_| [5.0, 15.0, 45.0]))
            .y_grid_spacer(egui_plot::uniform_grid_spacer(|_| [0.1, 0.5, 1.0]))
            .x_axis_formatter(|mark, _| format!("{:.0}°", mark.value))
            .y_axis_formatter(|mark, _| format!("{:.1}", mark.value))
            .x_axis_label("θ_i (°)")
            .y_axis_label("a(θ_i)")
            .show(ui, |plot| {
                plot.add(
                    Span::new("", 1.0..=top)
                        .axis(egui_plot::Axis::Y)
                        .fill(GAIN.gamma_multiply(0.18)),
                );
                plot.add(
                    Line::new("a = 1", PlotPoints::from(vec![[0.0, 1.0], [90.0, 1.0]]))
                        .color(GAIN)
                        .style(egui_plot::LineStyle::dashed_loose()),
                );
                for (c, a, colour) in &data {
                    plot.add(
                        Line::new(format!("{}a(θ_i)", c.name), PlotPoints::from(a.curve.clone()))
                            .color(*colour)
                            .width(2.5),
                    );
                    plot.add(
                        Points::new(
                            format!("{}{}", c.name, tr!("energy-lecture-angles")),
                            PlotPoints::from(a.table.clone()),
                        )
                        .radius(5.0)
                        .color(*colour)
                        .filled(true),
                    );
                }
            });
        ui.label(RichText::new(tr!("energy-red-band")).small().color(GAIN));
        egui::Grid::new("albedo table").striped(true).show(ui, |ui| {
            ui.label(RichText::new("θ_i").strong());
            for theta in LECTURE_ANGLES_DEG {
                ui.label(RichText::new(format!("{}°", number(theta))).size(14.0));
            }
            ui.end_row();
            for (c, a, colour) in &data {
                ui.label(RichText::new(format!("{}a(θ_i)", c.name)).strong().color(*colour))
                    .on_hover_text(tr!("energy-albedo-tip"));
                for [_, value] in &a.table {
                    let text = RichText::new(format!("{value:.3}")).monospace().size(14.0);
                    ui.label(if *value > 1.0 + 1e-9 {
                        text.color(GAIN).strong()
                    } else {
                        text
                    });
                }
                ui.end_row();
            }
        });

        ui.add_space(6.0);
        let default_source = tr!("energy-default-incidence");
        let (theta_i, source) = theta_i_deg.unwrap_or((45.0, default_source.as_str()));
        let theta_i = theta_i.clamp(0.0, MAX_THETA_DEG);
        ui.label(tr!("energy-lobe", theta = number(theta_i), source = source))
            .on_hover_text(tr!("energy-lobe-tip"));
        let lobes: Vec<(&Curve, Vec<[f64; 2]>, Color32)> = data
            .iter()
            .map(|(c, _, colour)| (*c, lobe_polar(&c.key, theta_i), *colour))
            .collect();
        let reach = lobes
            .iter()
            .flat_map(|(_, lobe, _)| lobe.iter().map(|p| p[0].hypot(p[1])))
            .fold(1e-9_f64, f64::max);
        let t = theta_i.to_radians();
        Plot::new("lobe plot")
            .height(200.0)
            .data_aspect(1.0)
            .allow_drag(false)
            .allow_zoom(false)
            .allow_scroll(false)
            .include_x(-reach)
            .include_x(reach)
            .include_y(0.0)
            .include_y(reach)
            .show(ui, |plot| {
                plot.add(
                    Line::new(
                        tr!("energy-light-l"),
                        PlotPoints::from(vec![[0.0, 0.0], [-t.sin() * reach, t.cos() * reach]]),
                    )
                    .color(Color32::from_rgb(230, 190, 40))
                    .width(2.0),
                );
                plot.add(
                    Line::new(
                        tr!("energy-normal-n"),
                        PlotPoints::from(vec![[0.0, 0.0], [0.0, reach]]),
                    )
                    .color(Color32::GRAY)
                    .style(egui_plot::LineStyle::dashed_dense()),
                );
                plot.add(
                    Line::new(
                        tr!("energy-surface"),
                        PlotPoints::from(vec![[-reach, 0.0], [reach, 0.0]]),
                    )
                    .color(Color32::GRAY),
                );
                for (c, lobe, colour) in lobes {
                    plot.add(
                        Line::new(format!("{}f_r(θ_o)", c.name), PlotPoints::from(lobe))
                            .color(colour)
                            .width(2.5),
                    );
                }
            });
        ui.label(tr!("energy-peak", peak = number(reach)));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lambert_albedo_is_k_everywhere() {
        let key = EnergyKey {
            k: 0.7,
            m: 10.0,
            norm: Normalization::Exact,
        };
        let mut lambert = key;
        lambert.k = 1.0;
        for [_, a] in albedo_curve(&lambert, [0.0, 45.0, 89.0]) {
            assert!((a - 1.0).abs() < 1e-9);
        }
        let mut panel = EnergyPanel::default();
        let i = panel.albedos(key);
        assert_eq!(panel.cache[i].table.len(), LECTURE_ANGLES_DEG.len());
        assert_eq!(panel.albedos(key), i, "cached");
    }

    #[test]
    fn the_lobe_peaks_at_the_mirror_direction() {
        let key = EnergyKey {
            k: 0.0,
            m: 1e4,
            norm: Normalization::Approx,
        };
        let lobe = lobe_polar(&key, 30.0);
        let peak = lobe
            .iter()
            .max_by(|a, b| (a[0].hypot(a[1])).total_cmp(&b[0].hypot(b[1])))
            .unwrap();
        let angle = peak[0].atan2(peak[1]).to_degrees();
        assert!((angle - 30.0).abs() < 0.2, "{angle}");
        let expected = Normalization::Approx.factor(1e4);
        assert!((peak[0].hypot(peak[1]) / expected - 1.0).abs() < 1e-3);
    }
}
