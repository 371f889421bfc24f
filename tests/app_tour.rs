//! The lecture tour: every step's command sets what the tour file
//! documents (as one undo step), opens and highlights its panel, and shows
//! the number `physics` gives for those settings; a malformed tour file is
//! a one-line error naming the step and the key; both languages have every
//! step's words.

use egui_kittest::kittest::{NodeT, Queryable};
use lumlab::app::{Command, SplitLayout, panel_title as title};
use lumlab::i18n::Language;
use lumlab::physics::energy::directional_albedo;
use lumlab::physics::radiometry::{incidence, intensity, sphere_irradiance, sphere_radiance};
use lumlab::physics::{BrdfParams, Normalization};
use lumlab::presets::ComparisonAxis;
use lumlab::settings::{BiasMode, DebugView, Filter, Settings, Visibility};
use lumlab::tour::{Observe, Tour, TourScene};
use std::f64::consts::PI;
use std::path::Path;

mod app_support;
use app_support::harness;

/// Frames enough for a step's scene, panels and grids to settle (a grid
/// takes a few frames to find its size when the panels change).
fn settle(harness: &mut egui_kittest::Harness<'_, lumlab::app::LabApp>) {
    harness.run_steps(12);
}

/// The observed quantity computed here from `physics` and `colour`
/// directly, from the settings the app shows.
fn expected(observe: &Observe, s: &Settings) -> f64 {
    let power = s.light.power_w as f64;
    let q = s.light.position.as_dvec3();
    match observe {
        Observe::Intensity => intensity(power),
        Observe::Irradiance { at, normal } => {
            let seen = incidence(at.as_dvec3(), normal.as_dvec3().normalize(), q);
            sphere_irradiance(power, s.light.radius_m as f64, seen.cos_theta, seen.r)
        }
        Observe::SphereRadiance => sphere_radiance(power, s.light.radius_m as f64),
        Observe::LightDistance { at } => (q - at.as_dvec3()).length(),
        Observe::Albedo { theta_deg } => {
            let params = BrdfParams {
                k: s.material.k as f64,
                m: s.material.m as f64,
                norm: s.material.norm,
            };
            directional_albedo(*theta_deg, &params).value
        }
        Observe::NormFactor => s.material.norm.factor(s.material.m as f64),
        Observe::DeltaE { illuminant } => {
            let rows = lumlab::colour::compare_chart(illuminant.parse().unwrap());
            rows.iter().map(|r| r.delta_e2000).sum::<f64>() / rows.len() as f64
        }
    }
}

fn step_index(tour: &Tour, id: &str) -> usize {
    tour.steps.iter().position(|s| s.id == id).unwrap()
}

#[test]
fn every_step_sets_its_settings_opens_its_panel_and_shows_the_physics() {
    let mut harness = harness();
    let tour = harness.state().tour().clone();
    assert!(
        tour.steps.len() >= 20,
        "the lecture has {} steps",
        tour.steps.len()
    );
    for (i, step) in tour.steps.iter().enumerate() {
        let before = harness.state().settings().clone();
        harness.state_mut().emit(Command::TourStep(i));
        settle(&mut harness);
        let app = harness.state();
        let shown = Settings {
            image: step.settings.image,
            ..app.settings().clone()
        };
        assert_eq!(shown, step.settings, "step {} ({})", i + 1, step.id);
        assert_eq!(app.tour_position(), (i, Some(step.panel)), "{}", step.id);
        // The panel is there and open (its header: other widgets may share
        // its title, e.g. the light's "Colour" beside the Colour section).
        let panel_title = title(step.panel);
        let expanded: Vec<_> = harness
            .query_all_by_label(&panel_title)
            .filter_map(|node| node.accesskit_node().data().is_expanded())
            .collect();
        assert_eq!(expanded, [true], "step {}: {} is not open", step.id, panel_title);
        // The number is physics' for the settings shown, and it is shown.
        let settings = harness.state().settings().clone();
        let value = harness.state_mut().tour_observed().unwrap();
        let truth = expected(&step.observe, &settings);
        assert!(
            (value - truth).abs() <= 1e-9 * truth.abs().max(1.0),
            "step {}: {value} against {truth}",
            step.id
        );
        let shown = Language::ALL.iter().any(|&language| {
            let number = step.observe.format(truth, language);
            let sentence = step.text(language).observe_with(&number);
            harness.query_by_label(&sentence).is_some()
        });
        assert!(shown, "step {}: the number {truth} is not shown", step.id);
        // One undo step: Ctrl+Z brings the settings before the step back.
        if before != harness.state().settings().clone() {
            harness.state_mut().emit(Command::Undo);
            settle(&mut harness);
            assert_eq!(harness.state().settings(), &before, "undo of {}", step.id);
            harness.state_mut().emit(Command::Redo);
            settle(&mut harness);
        }
    }
    the_lecture_panel_speaks_french();
}

#[test]
fn steps_set_what_the_lecture_shows() {
    let tour = Tour::built_in().unwrap();
    let step = |id: &str| &tour.steps[step_index(&tour, id)];
    // Known values (DESIGN.md): Lambert a = k; exact gives a(0°) = 1; approx
    // gives 1.075 at m = 8; I = Φ/4π.
    let approx = step("phong-approx");
    assert_eq!(approx.scene, TourScene::Spheres);
    assert_eq!(
        (
            approx.settings.material.norm,
            approx.settings.material.m,
            approx.settings.material.k
        ),
        (Normalization::Approx, 8.0, 0.0)
    );
    assert!((approx.observed(&approx.settings) - 1.075).abs() < 1e-3);
    let exact = step("phong-exact");
    assert!((exact.observed(&exact.settings) - 1.0).abs() < 1e-6);
    let lambert = step("lambert");
    assert!((lambert.observed(&lambert.settings) - 1.0).abs() < 1e-6);
    let flux = step("flux");
    assert!((flux.observed(&flux.settings) - 1000.0 / (4.0 * PI)).abs() < 1e-9);
    // Shadows: the presets' values and their comparisons side by side.
    let resolution = step("resolution");
    assert_eq!(resolution.settings.shadow.resolution, 256);
    assert_eq!(resolution.comparison.axis, ComparisonAxis::Resolution);
    assert_eq!(resolution.comparison.resolution, [256, 2048]);
    let acne = step("acne");
    assert_eq!(
        (acne.settings.shadow.bias.mode, acne.settings.shadow.bias.depth_m),
        (BiasMode::Constant, 0.0)
    );
    let penumbra = step("penumbra");
    assert_eq!(penumbra.settings.shadow.filter, Filter::Pcss);
    assert_eq!(penumbra.settings.light.radius_m, 0.4);
    assert_eq!(step("two-passes").settings.view.mode, DebugView::Depth);
    // Colour: the RGB product beside the spectral result, under tungsten.
    let colour = step("colour");
    assert_eq!(colour.comparison.axis, ComparisonAxis::Colour);
    assert_eq!(
        colour.settings.colour.illuminant,
        Some(lumlab::colour::Illuminant::A)
    );
    // Ray tracing: the shadow map beside GPU ray-traced V, under the sphere.
    let traced = step("ray-traced");
    assert_eq!(traced.comparison.axis, ComparisonAxis::Visibility);
    assert_eq!(
        traced.comparison.visibility,
        [Visibility::ShadowMap, Visibility::RayTraced]
    );
    assert!(traced.settings.light.radius_m > 0.0);
    // The lecture's figure: without | with normalization, side by side.
    let figure = step("with-without");
    assert_eq!(figure.comparison.axis, ComparisonAxis::Normalization);
    assert_eq!(
        figure.comparison.norm,
        [Normalization::None, Normalization::Approx]
    );
}

#[test]
fn a_side_by_side_step_shows_two_images_of_the_spheres() {
    let mut harness = harness();
    let index = step_index(harness.state().tour(), "with-without");
    harness.state_mut().emit(Command::TourStep(index));
    settle(&mut harness);
    let split = harness.state_mut().state_mut().split;
    assert!(split.enabled);
    assert_eq!(split.layout, SplitLayout::SideBySide);
    harness.get_by_label("A: norm none");
    harness.get_by_label("B: norm approx");
    // The scene is the spheres' row (the Scene panel names it).
    harness.get_by_label_contains("lecture spheres");
}

#[test]
fn both_languages_have_every_steps_words() {
    let tour = Tour::built_in().unwrap();
    for step in &tour.steps {
        let (fr, en) = (step.text(Language::Fr), step.text(Language::En));
        for (lang, t) in [("fr", fr), ("en", en)] {
            for (key, v) in [
                ("title", &t.title),
                ("text", &t.text),
                ("formula", &t.formula),
                ("observe", &t.observe),
                ("question", &t.question),
            ] {
                assert!(!v.trim().is_empty(), "{} {lang}.{key}", step.id);
            }
            assert!(t.observe.contains("{value}"), "{} {lang}.observe", step.id);
        }
        // Translated, not copied.
        assert_ne!(fr.text, en.text, "{}", step.id);
        assert_ne!(fr.question, en.question, "{}", step.id);
    }
}

/// The lecture panel in French, then in English again; every word of
/// every step drawable. Called by the walk through every step: the
/// language is process-wide, so no other test may switch it meanwhile.
fn the_lecture_panel_speaks_french() {
    let mut harness = harness();
    let tour = harness.state().tour().clone();
    let index = step_index(&tour, "phong-approx");
    lumlab::i18n::set_current(Language::Fr);
    harness.state_mut().emit(Command::TourStep(index));
    settle(&mut harness);
    let step = &tour.steps[index];
    harness.get_by_label(&step.text(Language::Fr).title);
    harness.get_by_label("Suivant ▶");
    // A decimal comma: 1,075.
    harness.get_by_label_contains("1,075");
    lumlab::i18n::set_current(Language::En);
    settle(&mut harness);
    harness.get_by_label(&step.text(Language::En).title);
    // Every word of every step can be drawn with the lab's fonts.
    let font = egui::FontId::proportional(20.0);
    for step in &tour.steps {
        for language in Language::ALL {
            let t = step.text(language);
            for text in [&t.title, &t.text, &t.formula, &t.observe, &t.question] {
                let drawable = harness.ctx.fonts_mut(|f| f.has_glyphs(&font, text));
                assert!(
                    drawable,
                    "{} ({language:?}): a glyph is missing in {text}",
                    step.id
                );
            }
        }
    }
}

/// The error of `text` as a tour file.
fn error_of(text: &str) -> String {
    let err = Tour::parse(text, Path::new("class.toml"))
        .unwrap_err()
        .to_string();
    assert!(!err.contains('\n'), "one line: {err}");
    assert!(err.starts_with("tour file 'class.toml'"), "{err}");
    err
}

/// The built-in tour with `from` replaced by `to` in the step `id`.
fn edited(id: &str, from: &str, to: &str) -> String {
    let text = lumlab::tour::BUILT_IN;
    let start = text.find(&format!("id = \"{id}\"")).unwrap();
    let at = start + text[start..].find(from).unwrap();
    format!("{}{to}{}", &text[..at], &text[at + from.len()..])
}

#[test]
fn a_malformed_tour_file_is_one_line_naming_the_step_and_the_key() {
    let tour = Tour::built_in().unwrap();
    let number = |id: &str| format!("step {} ('{id}')", step_index(&tour, id) + 1);
    let cases = [
        // An unknown key in a step.
        (
            edited("lambert", "panel = \"energy\"", "panel = \"energy\"\ncolour = 3"),
            "lambert",
            "colour",
        ),
        // An unknown key among the settings.
        (
            edited("mixed", "k = 0.5", "k = 0.5, shininess = 4"),
            "mixed",
            "shininess",
        ),
        // A wrong type.
        (edited("mixed", "m = 32.0", "m = \"shiny\""), "mixed", "m"),
        // A value out of range.
        (edited("mixed", "k = 0.5", "k = 1.5"), "mixed", "material.k"),
        // An unknown panel.
        (
            edited("flux", "panel = \"light\"", "panel = \"lamp\""),
            "flux",
            "panel",
        ),
        // An unknown quantity to observe.
        (
            edited("flux", "quantity = \"intensity\"", "quantity = \"brightness\""),
            "flux",
            "observe",
        ),
        // The observe sentence without its number.
        (
            edited("flux", "intensité I = {value}", "intensité I"),
            "flux",
            "fr.observe",
        ),
        // Missing English words.
        (
            edited("flux", "title = \"Radiometry", "titel = \"Radiometry"),
            "flux",
            "titel",
        ),
        // An empty question.
        (
            edited(
                "flux",
                "question = \"If Φ doubles, what happens to I? To the image?\"",
                "question = \" \"",
            ),
            "flux",
            "en.question",
        ),
        // A step id used twice.
        (
            edited("irradiance", "id = \"irradiance\"", "id = \"flux\""),
            "flux",
            "id",
        ),
    ];
    for (text, id, key) in cases {
        let err = error_of(&text);
        let step = if key == "id" {
            format!("step {}", step_index(&tour, "irradiance") + 1)
        } else {
            number(id)
        };
        assert!(err.contains(&step), "{step} not named: {err}");
        assert!(err.contains(key), "{key} not named: {err}");
    }
    assert!(error_of("").contains("step"));
}

#[test]
fn a_bad_tour_file_stops_the_lab_before_its_window_with_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("class.toml");
    std::fs::write(&path, edited("mixed", "k = 0.5", "k = 1.5")).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_lumlab"))
        .arg("--tour")
        .arg(&path)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("'mixed'") && stderr.contains("material.k"),
        "{stderr}"
    );
}
