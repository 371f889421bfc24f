//! Writes the built-in scene to `assets/default_scene.glb` (run from the
//! crate root: `cargo run --example make_default_scene`). The scene itself
//! is built in `lumlab::scene::default_scene`; commit the asset it writes.

use lumlab::scene::default_scene;
use std::path::Path;

fn main() -> anyhow::Result<()> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(default_scene::ASSET_PATH);
    let bytes = default_scene::build();
    lumlab::output::write_atomically(&path, &bytes)?;
    println!("wrote {} ({} bytes)", path.display(), bytes.len());
    Ok(())
}
