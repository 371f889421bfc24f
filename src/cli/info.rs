//! `lumlab info`: the facts of a scene (counts, bounds, objects, cameras,
//! what the loader repaired), as text for people or JSON for scripts.

use crate::scene::{self, SceneFacts};
use anyhow::Context;
use std::fmt::Write;
use std::path::PathBuf;
use std::time::Instant;

named_enum! {
    /// Output format of `lumlab info`.
    pub enum InfoFormat {
        Text = "text",
        Json = "json",
    }
}

#[derive(Debug, clap::Args)]
pub struct InfoArgs {
    /// glTF or GLB scene (default: the built-in scene).
    #[arg(long, value_name = "FILE.gltf|FILE.glb")]
    pub scene: Option<PathBuf>,
    /// text (for people) or json.
    #[arg(long, value_name = "FORMAT", default_value = "text", value_parser = format)]
    pub format: InfoFormat,
}

fn format(text: &str) -> Result<InfoFormat, String> {
    text.parse()
}

pub fn run(args: &InfoArgs) -> anyhow::Result<()> {
    let start = Instant::now();
    let (scene, name) = match &args.scene {
        Some(path) => (scene::load(path)?, path.display().to_string()),
        None => (scene::default_scene(), "built-in scene".to_string()),
    };
    let load = Load {
        seconds: start.elapsed().as_secs_f64(),
        peak_mib: peak_memory_mib(),
    };
    let facts = scene.facts();
    let text = match args.format {
        InfoFormat::Text => text(&name, &facts) + &load.line(),
        InfoFormat::Json => serde_json::to_string_pretty(&facts).context("cannot format the facts")? + "\n",
    };
    print!("{text}");
    Ok(())
}

/// What loading the scene took: not a fact of the scene, so in the text
/// only (the JSON stays the same for the same file).
struct Load {
    seconds: f64,
    peak_mib: Option<f64>,
}

impl Load {
    fn line(&self) -> String {
        let memory = self
            .peak_mib
            .map_or(String::new(), |mib| format!(", peak memory {mib:.0} MiB"));
        format!("loaded     in {:.3} s{memory}\n", self.seconds)
    }
}

/// The process's peak resident memory so far in MiB: `VmHWM` of
/// /proc/self/status (Linux; None elsewhere).
fn peak_memory_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}

fn xyz(v: Option<[f32; 3]>) -> String {
    match v {
        Some([x, y, z]) => format!("({x:.4}, {y:.4}, {z:.4})"),
        None => "-".into(),
    }
}

fn yes_no(flag: bool) -> &'static str {
    if flag { "yes" } else { "no" }
}

fn text(name: &str, f: &SceneFacts) -> String {
    let mut out = String::new();
    let scene = f
        .scene
        .map_or("root nodes".to_string(), |s| format!("scene {s} of {}", f.scenes));
    // Writing to a String cannot fail.
    let _ = writeln!(out, "scene      {name} ({scene}, {} nodes)", f.nodes);
    let _ = writeln!(
        out,
        "meshes     {} ({} primitives, normals: {})",
        f.meshes, f.primitives, f.has_normals
    );
    let _ = writeln!(out, "triangles  {}", f.triangles);
    let _ = writeln!(out, "bounds     {} … {} m", xyz(f.bounds_min), xyz(f.bounds_max));
    let _ = writeln!(out, "materials  {} ({} textures)", f.materials, f.textures);
    let _ = writeln!(out, "cameras    {}", f.cameras);
    for c in &f.camera_list {
        let _ = writeln!(
            out,
            "  {}: eye {} target {} fovy {:.1}°",
            c.name,
            xyz(Some(c.eye)),
            xyz(Some(c.target)),
            c.fovy_deg
        );
    }
    let _ = writeln!(out, "objects    {}", f.objects.len());
    let width = f
        .objects
        .iter()
        .map(|o| o.name.chars().count())
        .max()
        .unwrap_or(0);
    for o in &f.objects {
        let _ = writeln!(
            out,
            "  {:width$}  {:>8} triangles  {} … {}  material '{}'  casts {}  receives {}",
            o.name,
            o.triangles,
            xyz(o.bounds_min),
            xyz(o.bounds_max),
            o.material,
            yes_no(o.casts_shadows),
            yes_no(o.receives_shadows),
        );
    }
    if f.warnings.is_empty() {
        let _ = writeln!(out, "warnings   none");
    } else {
        let _ = writeln!(out, "warnings   {}", f.warnings.len());
        for w in &f.warnings {
            let _ = writeln!(out, "  {w}");
        }
    }
    out
}
