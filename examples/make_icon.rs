//! Writes the application icon to `assets/icon.png` (run from the crate
//! root: `cargo run --example make_icon`). The icon is drawn in
//! `lumlab::app::icon`; commit the file it writes.

use lumlab::app::icon;
use std::path::Path;

fn main() -> anyhow::Result<()> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(icon::ASSET_PATH);
    lumlab::image_io::write_png_rgba8(&path, &icon::draw(icon::SIZE))?;
    println!("wrote {}", path.display());
    Ok(())
}
