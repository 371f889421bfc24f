//! The public sample models in `../shared/gltf-samples` (beside the crate)
//! against the facts `expected.json` gives for each; skipped where that
//! folder is absent. The samples are never copied into the repository.

mod scene_support;

use lumlab::scene::{self, SceneFacts};
use scene_support::samples::{check, expected_models, samples_dir};

#[test]
fn every_sample_model_gives_its_expected_facts() {
    let Some(dir) = samples_dir() else {
        eprintln!("no ../shared/gltf-samples: skipped");
        return;
    };
    let models = expected_models(&dir);
    assert!(models.len() >= 20, "{} models", models.len());
    let mut failures = Vec::new();
    for (model, expected) in &models {
        let facts: SceneFacts = match scene::load(&dir.join(model)) {
            Ok(s) => s.facts(),
            Err(e) => {
                failures.push(format!("{model}: {e}"));
                continue;
            }
        };
        if let Err(e) = check(model, &serde_json::to_value(&facts).unwrap(), expected) {
            failures.push(e);
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
