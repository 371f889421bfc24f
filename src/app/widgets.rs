//! Small building blocks the panels share: numbers with units, read-only
//! value rows with a formula tooltip, a logarithmic slider that also offers 0.

use crate::tr;
use egui::{RichText, Ui};

/// A number with four significant digits, switching to scientific notation
/// outside 0.001 … 99 999: what every read-out in the lab uses.
pub fn number(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    if !x.is_finite() {
        return format!("{x}");
    }
    let a = x.abs();
    if (1e-3..1e5).contains(&a) {
        let decimals = (3 - a.log10().floor() as i32).clamp(0, 6) as usize;
        let text = format!("{x:.decimals$}");
        if text.contains('.') {
            text.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            text
        }
    } else {
        let text = format!("{x:.3e}");
        // 1.000e4 → 1e4: trailing zeros of the mantissa say nothing.
        match text.split_once('e') {
            Some((mantissa, exp)) if mantissa.contains('.') => {
                format!("{}e{exp}", mantissa.trim_end_matches('0').trim_end_matches('.'))
            }
            _ => text,
        }
    }
}

/// `number` followed by its unit.
pub fn quantity(x: f64, unit: &str) -> String {
    with_unit(number(x), unit)
}

/// The unit a length of magnitude `metres` reads best in: mm below 10 cm,
/// km from 10 km, m between; with its factor from metres.
fn length_unit(metres: f64) -> (f64, &'static str) {
    let a = metres.abs();
    if a > 0.0 && a < 0.1 {
        (1e3, "mm")
    } else if a >= 1e4 {
        (1e-3, "km")
    } else {
        (1.0, "m")
    }
}

/// A length (m) in mm, m or km, whichever reads best (a model in
/// millimetres or a far sun stay readable).
pub fn length(metres: f64) -> String {
    let (factor, unit) = length_unit(metres);
    quantity(metres * factor, unit)
}

/// A position (m), its unit chosen by its largest component.
pub fn position(v: glam::DVec3) -> String {
    let (factor, unit) = length_unit(v.abs().max_element());
    vector(v * factor, unit)
}

/// `text` followed by its unit, if any.
fn with_unit(text: String, unit: &str) -> String {
    if unit.is_empty() {
        text
    } else {
        format!("{text} {unit}")
    }
}

/// A vector as (x, y, z) with its unit; components below 10⁻⁹ of the
/// largest are rounding noise and show as 0.
pub fn vector(v: glam::DVec3, unit: &str) -> String {
    let floor = v.abs().max_element() * 1e-9;
    let c = |x: f64| number(if x.abs() <= floor { 0.0 } else { x });
    with_unit(format!("({}, {}, {})", c(v.x), c(v.y), c(v.z)), unit)
}

/// An RGB quantity: one number when the three channels read the same.
pub fn rgb(v: glam::DVec3, unit: &str) -> String {
    let (r, g, b) = (number(v.x), number(v.y), number(v.z));
    let text = if r == g && g == b {
        format!("{r} (r = g = b)")
    } else {
        format!("({r}, {g}, {b})")
    };
    with_unit(text, unit)
}

/// One row of a read-out grid: the symbol, the value (monospace, selectable)
/// and the formula as tooltip on both.
pub fn value_row(ui: &mut Ui, symbol: &str, value: &str, formula: &str) {
    ui.label(RichText::new(symbol).strong()).on_hover_text(formula);
    ui.add(egui::Label::new(RichText::new(value).monospace()).selectable(true))
        .on_hover_text(formula);
    ui.end_row();
}

/// A logarithmic slider over `0 ..= max` (the smallest positive step is
/// `smallest`) with an explicit "0" button beside it, since a log scale
/// cannot reach 0 by dragging. Returns true when the value changed.
pub fn log_slider_with_zero(
    ui: &mut Ui,
    label: egui::Id,
    value: &mut f32,
    smallest: f64,
    max: f64,
    unit: &str,
    tooltip: &str,
) -> bool {
    let before = *value;
    ui.horizontal(|ui| {
        ui.add(
            egui::Slider::new(value, 0.0..=max as f32)
                .logarithmic(true)
                .smallest_positive(smallest)
                .suffix(unit)
                .custom_formatter(|x, _| number(x)),
        )
        .labelled_by(label)
        .on_hover_text(tooltip);
        if ui
            .add_enabled(*value != 0.0, egui::Button::new("0"))
            .on_hover_text(tr!("slider-zero-tip"))
            .clicked()
        {
            *value = 0.0;
        }
    });
    *value != before
}

/// A heading-sized derived value, e.g. "I = 79.58 W/sr".
pub fn derived(ui: &mut Ui, text: &str, formula: &str) {
    ui.label(RichText::new(text).monospace()).on_hover_text(formula);
}

/// A warning line (orange), e.g. a clamped resolution.
pub fn warning(ui: &mut Ui, text: &str) {
    ui.label(RichText::new(text).color(ui.visuals().warn_fg_color));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_keep_four_significant_digits() {
        assert_eq!(number(0.0), "0");
        assert_eq!(number(79.577_471), "79.58");
        assert_eq!(number(1000.0), "1000");
        assert_eq!(number(0.012_345_6), "0.01235");
        assert_eq!(number(2.5), "2.5");
        assert_eq!(number(-3.0), "-3");
        assert_eq!(number(1e6), "1e6");
        assert_eq!(number(1.25e-5), "1.25e-5");
        assert_eq!(quantity(1.0, "W"), "1 W");
        assert_eq!(vector(glam::DVec3::new(0.5, -4e-16, 3.0), "m"), "(0.5, 0, 3) m");
        assert_eq!(length(0.0025), "2.5 mm");
        assert_eq!(length(3.0), "3 m");
        assert_eq!(length(1.5e11), "1.5e8 km");
        assert_eq!(position(glam::DVec3::new(0.002, 0.001, 0.0)), "(2, 1, 0) mm");
        assert_eq!(rgb(glam::DVec3::splat(0.25), "W"), "0.25 (r = g = b) W");
        assert_eq!(rgb(glam::DVec3::new(1.0, 2.0, 3.0), ""), "(1, 2, 3)");
    }
}
