//! The language of the app's text: French (the course's language) or
//! English. One process-wide current language, read by every panel and by
//! the lecture tour, set by the language menu (and restored from the
//! persisted state at start-up).

mod text;

pub use text::{FluentValue, MessageInfo, messages, source, tr, tr_args, translate};

use serde::{Deserialize, Serialize};
use std::sync::atomic::{AtomicU8, Ordering};

/// A language the app's text exists in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Language {
    /// Français: the course is taught in French.
    Fr,
    #[default]
    En,
}

impl Language {
    pub const ALL: [Language; 2] = [Language::Fr, Language::En];

    /// The ISO 639-1 code ("fr", "en").
    pub fn code(self) -> &'static str {
        match self {
            Language::Fr => "fr",
            Language::En => "en",
        }
    }

    /// The language's name in itself, for the language menu.
    pub fn native_name(self) -> &'static str {
        match self {
            Language::Fr => "Français",
            Language::En => "English",
        }
    }

    /// The language of a locale tag such as `fr-FR`, `fr_CA.UTF-8` or
    /// `en-GB`: French for any French locale, English otherwise.
    pub fn from_locale(tag: &str) -> Self {
        let primary = tag.split(['-', '_', '.', '@']).next().unwrap_or_default();
        if primary.eq_ignore_ascii_case("fr") {
            Language::Fr
        } else {
            Language::En
        }
    }
}

/// The language of the system's locale (`LC_ALL`, `LC_MESSAGES`, `LANG` on
/// Unix): the app's language until the user picks one.
pub fn system_language() -> Language {
    sys_locale::get_locale().map_or(Language::En, |tag| Language::from_locale(&tag))
}

static CURRENT: AtomicU8 = AtomicU8::new(Language::En as u8);

/// The language the app's text is shown in now.
pub fn current() -> Language {
    match CURRENT.load(Ordering::Relaxed) {
        x if x == Language::Fr as u8 => Language::Fr,
        _ => Language::En,
    }
}

/// Shows the app's text in `language` from the next frame on.
pub fn set_current(language: Language) {
    CURRENT.store(language as u8, Ordering::Relaxed);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn locale_tags_map_to_their_language() {
        for tag in ["fr", "fr-FR", "fr_CA.UTF-8", "FR", "fr@euro"] {
            assert_eq!(Language::from_locale(tag), Language::Fr, "{tag}");
        }
        for tag in ["en-US", "de_DE.UTF-8", "", "C", "POSIX", "french"] {
            assert_eq!(Language::from_locale(tag), Language::En, "{tag}");
        }
    }
}
