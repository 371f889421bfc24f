//! The app's text in French and English: both Fluent files parse and have
//! the same keys with the same placeholders, no message is empty, every key
//! the code names exists; in the window, French shows in the panels and the
//! language picked survives a store and restore of the app state.

mod app_support;

use app_support::harness_with_storage;
use egui_kittest::kittest::Queryable;
use lumlab::app::{Command, MemoryStorage, State};
use lumlab::i18n::{self, Language, MessageInfo};
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use std::sync::Mutex;

/// The tests that change the process-wide language run one at a time.
static LANGUAGE: Mutex<()> = Mutex::new(());

fn messages(language: Language) -> BTreeMap<String, MessageInfo> {
    let list = i18n::messages(language).unwrap_or_else(|e| panic!("{e}"));
    let mut map = BTreeMap::new();
    for message in list {
        let key = message.key.clone();
        assert!(
            map.insert(key.clone(), message).is_none(),
            "{}: '{key}' twice",
            language.code()
        );
    }
    map
}

#[test]
fn both_languages_have_the_same_keys() {
    let fr: BTreeSet<_> = messages(Language::Fr).into_keys().collect();
    let en: BTreeSet<_> = messages(Language::En).into_keys().collect();
    let only_fr: Vec<_> = fr.difference(&en).collect();
    let only_en: Vec<_> = en.difference(&fr).collect();
    assert!(
        only_fr.is_empty() && only_en.is_empty(),
        "only in fr: {only_fr:?}; only in en: {only_en:?}"
    );
    assert!(en.len() > 100, "{} messages: the files are not read", en.len());
}

#[test]
fn placeholders_match_between_languages() {
    let fr = messages(Language::Fr);
    for (key, en) in messages(Language::En) {
        if let Some(fr) = fr.get(&key) {
            assert_eq!(fr.placeholders, en.placeholders, "placeholders of '{key}'");
        }
    }
}

#[test]
fn no_message_is_empty() {
    for language in Language::ALL {
        for (key, message) in messages(language) {
            assert!(!message.empty, "{}: '{key}' is empty", language.code());
        }
    }
}

/// The keys named in `text` by `tr!("KEY"`, `tr("KEY"` or `tr_args("KEY"`.
fn keys_in(text: &str) -> Vec<String> {
    let mut keys = Vec::new();
    for call in ["tr!(", "tr(", "tr_args("] {
        for (at, _) in text.match_indices(call) {
            let before = text[..at].chars().next_back();
            if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
                continue; // e.g. `attr(`, `str(`
            }
            let rest = text[at + call.len()..].trim_start();
            if let Some(quoted) = rest.strip_prefix('"')
                && let Some(end) = quoted.find('"')
            {
                keys.push(quoted[..end].to_owned());
            }
        }
    }
    keys
}

fn rust_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn the_scan_finds_keys_in_every_form_of_call() {
    let code = r#"tr!("a"); tr!(
        "b", n = 1); i18n::tr("c"); tr_args("d", &[]); attr("e"); tr!(KEY)"#;
    assert_eq!(keys_in(code), ["a", "b", "c", "d"]);
}

#[test]
fn every_key_the_code_uses_exists() {
    let en = messages(Language::En);
    let fr = messages(Language::Fr);
    let mut files = Vec::new();
    rust_files(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src"), &mut files);
    let mut used = 0;
    let mut missing = Vec::new();
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        for key in keys_in(&text) {
            used += 1;
            if !en.contains_key(&key) || !fr.contains_key(&key) {
                missing.push(format!("{}: {key}", file.display()));
            }
        }
    }
    assert!(
        missing.is_empty(),
        "keys missing from the .ftl files:\n{}",
        missing.join("\n")
    );
    assert!(used > 100, "only {used} keys found in src/: the scan is broken");
}

#[test]
fn messages_place_their_arguments_in_both_languages() {
    let args = [
        ("first", i18n::FluentValue::from("q inside a box")),
        ("more", 2.into()),
    ];
    assert_eq!(
        i18n::translate(Language::En, "status-impossible-more", &args),
        "Impossible set-up: q inside a box (+2 more)"
    );
    assert_eq!(
        i18n::translate(Language::Fr, "status-impossible-more", &args),
        "Configuration impossible : q inside a box (+2 autres)"
    );
}

#[test]
fn french_shows_in_the_panels_and_survives_a_restart() {
    let _one_at_a_time = LANGUAGE.lock().unwrap_or_else(|e| e.into_inner());
    i18n::set_current(Language::En);
    let mut harness = harness_with_storage(None);
    assert!(harness.query_all_by_label("Power Φ").count() >= 1);

    harness.state_mut().emit(Command::SetLanguage(Language::Fr));
    harness.run();
    assert_eq!(i18n::current(), Language::Fr);
    assert!(
        harness.query_all_by_label("Flux Φ").count() >= 1,
        "the Light panel in French"
    );
    assert!(
        harness.query_all_by_label("Ombres").count() >= 1,
        "the Shadow panel in French"
    );
    assert_eq!(
        harness.query_all_by_label("Power Φ").count(),
        0,
        "no English left in the Light panel"
    );

    // The app stores its state on exit; the next start restores it.
    let mut storage = MemoryStorage::default();
    harness.state_mut().state_mut().store(&mut storage);
    drop(harness);
    assert_eq!(
        State::restore(Some(&storage)).unwrap().language,
        Some(Language::Fr)
    );
    i18n::set_current(Language::En);
    let harness = harness_with_storage(Some(&storage));
    assert_eq!(
        i18n::current(),
        Language::Fr,
        "the stored language is the one shown"
    );
    assert!(harness.query_all_by_label("Flux Φ").count() >= 1);
    drop(harness);
    i18n::set_current(Language::En);
}

#[test]
fn reset_everything_keeps_the_language() {
    let _one_at_a_time = LANGUAGE.lock().unwrap_or_else(|e| e.into_inner());
    let mut harness = harness_with_storage(None);
    harness.state_mut().emit(Command::SetLanguage(Language::Fr));
    harness.run();
    harness.state_mut().emit(Command::ResetEverything);
    harness.run();
    assert_eq!(i18n::current(), Language::Fr);
    assert_eq!(harness.state_mut().state_mut().language, Some(Language::Fr));
    drop(harness);
    i18n::set_current(Language::En);
}
