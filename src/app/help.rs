//! The keyboard shortcuts and mouse gestures, listed in one place: the help
//! window shows this table, and the app's key handling follows it.

/// (keys, what they do).
pub const SHORTCUTS: &[(&str, &str)] = &[
    ("F1 or ?", "this help"),
    ("Left drag", "orbit the camera around its target"),
    ("Shift + drag / middle drag", "pan"),
    ("Wheel", "zoom"),
    ("Click", "probe the pixel (every term of L = f_r · E · V)"),
    ("Drag the yellow light", "move the light parallel to the image"),
    ("Ctrl + drag the light", "move the light up and down"),
    ("R", "reset the view"),
    ("S", "split view A | B on/off"),
    ("V / Shift+V", "next / previous debug view"),
    ("Ctrl+Z", "undo a settings change"),
    ("Ctrl+Shift+Z or Ctrl+Y", "redo"),
    ("Ctrl+S", "save the settings file"),
    ("Ctrl+O", "open the glTF/GLB in the scene path"),
    ("F5", "compute the CPU reference"),
    ("Esc", "cancel the reference / close this help"),
    ("F12", "save a screenshot"),
    ("F9", "hide/show the side panels"),
];

pub fn window(ctx: &egui::Context, open: &mut bool) {
    egui::Window::new("Keyboard and mouse")
        .open(open)
        .collapsible(false)
        .resizable(false)
        .anchor(egui::Align2::CENTER_CENTER, [0.0, 0.0])
        .show(ctx, |ui| {
            egui::Grid::new("shortcuts")
                .num_columns(2)
                .striped(true)
                .show(ui, |ui| {
                    for (keys, action) in SHORTCUTS {
                        ui.label(egui::RichText::new(*keys).strong().monospace());
                        ui.label(*action);
                        ui.end_row();
                    }
                });
            ui.add_space(6.0);
            ui.label("Every number has its unit; hover a control or a value to see its formula.");
        });
}
