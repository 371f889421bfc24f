//! The app's text as Fluent messages: `assets/i18n/en.ftl` and `fr.ftl`,
//! each followed by its `-views.ftl` (the viewport, lecture, timings,
//! colour and tour texts), embedded in the binary, one bundle per language
//! built once. Code names a
//! message by its key (`tr!("light-power")`, `tr!("error-scene-kept", message =
//! e.to_string())`); the message is looked up in the current language.
//!
//! A key missing from the files shows as the key itself, visibly wrong in
//! the UI; `tests/app_i18n.rs` checks that every key the code uses exists,
//! that both files have the same keys and the same placeholders, and that
//! no message is empty.
//!
//! Numbers are formatted by the code before they reach a message, with a
//! decimal point in both languages (the sliders and fields parse "."), so
//! the files only place them; counts are passed as numbers so that plurals
//! can select on them.

use super::{Language, current};
use fluent_bundle::concurrent::FluentBundle;
use fluent_bundle::{FluentArgs, FluentResource};
use fluent_syntax::ast;
use std::collections::BTreeSet;
use std::sync::OnceLock;

pub use fluent_bundle::FluentValue;

/// The Fluent source of `language`'s messages.
pub fn source(language: Language) -> &'static str {
    match language {
        Language::Fr => concat!(
            include_str!("../../assets/i18n/fr.ftl"),
            "\n",
            include_str!("../../assets/i18n/fr-views.ftl")
        ),
        Language::En => concat!(
            include_str!("../../assets/i18n/en.ftl"),
            "\n",
            include_str!("../../assets/i18n/en-views.ftl")
        ),
    }
}

type Bundle = FluentBundle<FluentResource>;

fn bundle(language: Language) -> &'static Bundle {
    static BUNDLES: OnceLock<[Bundle; 2]> = OnceLock::new();
    let [fr, en] = BUNDLES.get_or_init(|| [build(Language::Fr), build(Language::En)]);
    match language {
        Language::Fr => fr,
        Language::En => en,
    }
}

fn build(language: Language) -> Bundle {
    // A syntax error keeps the messages that parsed; the tests fail on it.
    let resource =
        FluentResource::try_new(source(language).to_owned()).unwrap_or_else(|(partial, _errors)| partial);
    let locale = language.code().parse().unwrap_or_default();
    let mut bundle = FluentBundle::new_concurrent(vec![locale]);
    // Unicode isolation marks around placed values show as boxes in egui.
    bundle.set_use_isolating(false);
    // A duplicate key keeps its first message; the tests fail on it.
    let _ = bundle.add_resource(resource);
    bundle
}

/// The message `key` in the current language (the key itself if missing).
pub fn tr(key: &str) -> String {
    translate(current(), key, &[])
}

/// The message `key` in the current language, its `{ $name }`
/// placeholders replaced by `args`.
pub fn tr_args(key: &str, args: &[(&str, FluentValue)]) -> String {
    translate(current(), key, args)
}

/// The message `key` in `language`, with `args` placed (the key itself if
/// `language` has no such message).
pub fn translate(language: Language, key: &str, args: &[(&str, FluentValue)]) -> String {
    let bundle = bundle(language);
    let Some(pattern) = bundle.get_message(key).and_then(|m| m.value()) else {
        return key.to_owned();
    };
    let mut fluent_args = FluentArgs::new();
    for (name, value) in args {
        fluent_args.set(*name, value.clone());
    }
    // A placeholder without its argument shows as `{$name}`: visible too.
    let mut errors = Vec::new();
    bundle
        .format_pattern(pattern, Some(&fluent_args), &mut errors)
        .into_owned()
}

/// `tr!(KEY)` or `tr!(KEY, name = value, ...)`: the message in the
/// current language. Values are strings (numbers formatted with their
/// unit by the caller) or integers (counts, for plurals).
#[macro_export]
macro_rules! tr {
    ($key:literal) => {
        $crate::i18n::tr($key)
    };
    ($key:literal, $($name:ident = $value:expr),+ $(,)?) => {
        $crate::i18n::tr_args(
            $key,
            &[$((stringify!($name), $crate::i18n::FluentValue::from($value))),+],
        )
    };
}

/// One message of a Fluent file, as the consistency tests see it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MessageInfo {
    pub key: String,
    /// The `{ $name }` variables it places (in any variant).
    pub placeholders: BTreeSet<String>,
    /// It has no value, or only blanks.
    pub empty: bool,
}

/// Every message of `language`'s file in order, or the file's syntax errors.
pub fn messages(language: Language) -> Result<Vec<MessageInfo>, String> {
    let resource = FluentResource::try_new(source(language).to_owned()).map_err(|(_, errors)| {
        let shown: Vec<String> = errors.iter().map(|e| format!("{e:?}")).collect();
        format!("{}.ftl: {}", language.code(), shown.join("; "))
    })?;
    Ok(resource
        .entries()
        .filter_map(|entry| match entry {
            ast::Entry::Message(message) => Some(message_info(message)),
            _ => None,
        })
        .collect())
}

fn message_info(message: &ast::Message<&str>) -> MessageInfo {
    let mut placeholders = BTreeSet::new();
    let mut text = String::new();
    if let Some(pattern) = &message.value {
        walk_pattern(pattern, &mut placeholders, &mut text);
    }
    MessageInfo {
        key: message.id.name.to_owned(),
        empty: text.trim().is_empty() && placeholders.is_empty(),
        placeholders,
    }
}

fn walk_pattern(pattern: &ast::Pattern<&str>, vars: &mut BTreeSet<String>, text: &mut String) {
    for element in &pattern.elements {
        match element {
            ast::PatternElement::TextElement { value } => text.push_str(value),
            ast::PatternElement::Placeable { expression } => walk_expression(expression, vars, text),
        }
    }
}

fn walk_expression(expression: &ast::Expression<&str>, vars: &mut BTreeSet<String>, text: &mut String) {
    match expression {
        ast::Expression::Select { selector, variants } => {
            walk_inline(selector, vars, text);
            for variant in variants {
                walk_pattern(&variant.value, vars, text);
            }
        }
        ast::Expression::Inline(inline) => walk_inline(inline, vars, text),
    }
}

fn walk_inline(inline: &ast::InlineExpression<&str>, vars: &mut BTreeSet<String>, text: &mut String) {
    match inline {
        ast::InlineExpression::VariableReference { id } => {
            vars.insert(id.name.to_owned());
        }
        ast::InlineExpression::StringLiteral { value } => text.push_str(value),
        ast::InlineExpression::Placeable { expression } => walk_expression(expression, vars, text),
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_message_reads_in_each_language() {
        assert_eq!(translate(Language::En, "menu-language", &[]), "Language");
        assert_eq!(translate(Language::Fr, "menu-language", &[]), "Langue");
    }

    #[test]
    fn a_missing_key_shows_as_itself() {
        assert_eq!(translate(Language::Fr, "no-such-key", &[]), "no-such-key");
    }

    #[test]
    fn placeholders_are_placed_without_isolation_marks() {
        let args = [("message", FluentValue::from("disk full"))];
        assert_eq!(
            translate(Language::Fr, "error-scene-kept", &args),
            "disk full ; la scène actuelle est conservée"
        );
        assert_eq!(
            translate(Language::En, "error-scene-kept", &args),
            "disk full; the current scene is kept"
        );
    }

    #[test]
    fn counts_select_the_plural() {
        let more = |n: i64, language| {
            translate(
                language,
                "status-impossible-more",
                &[("first", FluentValue::from("x")), ("more", FluentValue::from(n))],
            )
        };
        assert_eq!(more(1, Language::En), "Impossible set-up: x (+1 more)");
        assert_eq!(more(1, Language::Fr), "Configuration impossible : x (+1 autre)");
        assert_eq!(more(3, Language::Fr), "Configuration impossible : x (+3 autres)");
        let rays = |n: u32, language| {
            let args = [
                ("frames", FluentValue::from(1)),
                ("max", FluentValue::from(64)),
                ("rays", FluentValue::from(n)),
                ("noise", FluentValue::from("σ")),
            ];
            translate(language, "visibility-accumulation", &args)
        };
        assert_eq!(rays(1, Language::En), "1 / 64 frames × 1 ray, σ");
        assert_eq!(rays(4, Language::En), "1 / 64 frames × 4 rays, σ");
        assert_eq!(rays(1, Language::Fr), "1 / 64 images × 1 rayon, σ");
        assert_eq!(rays(4, Language::Fr), "1 / 64 images × 4 rayons, σ");
    }
}
