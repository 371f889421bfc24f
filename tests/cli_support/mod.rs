//! Shared by the command-line tests: the `lumlab` binary run with arguments
//! (and environment variables), its output as text, and its CSV read back.
#![allow(dead_code)]

use std::collections::HashMap;
use std::path::Path;
use std::process::{Command, Output};

/// Runs the binary with `args`.
pub fn lumlab(args: &[&str]) -> Output {
    lumlab_with_env(args, &[])
}

/// Runs the binary with `args` and the environment variables `env` added.
pub fn lumlab_with_env(args: &[&str], env: &[(&str, &str)]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lumlab"))
        .args(args)
        .envs(env.iter().copied())
        .output()
        .expect("the lumlab binary runs")
}

pub fn stdout(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

pub fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// stderr's lines without the software driver's XDG_RUNTIME_DIR warnings.
pub fn stderr_lines(out: &Output) -> Vec<String> {
    stderr(out)
        .lines()
        .filter(|l| !l.contains("XDG_RUNTIME_DIR"))
        .map(str::to_string)
        .collect()
}

/// Fails with `code` and one line on stderr (the driver's notes aside)
/// that mentions `mentions`.
pub fn assert_refused(out: &Output, code: i32, mentions: &str) {
    let lines = stderr_lines(out);
    assert_eq!(out.status.code(), Some(code), "{lines:?}");
    assert_eq!(lines.len(), 1, "not one line: {lines:?}");
    assert!(
        lines[0].contains(mentions),
        "'{}' does not mention {mentions}",
        lines[0]
    );
}

/// The names of the entries of `dir`, sorted.
pub fn names_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// The fields of one CSV line (quoted fields may hold commas, and `""` in
/// them stands for one quote).
pub fn csv_fields(line: &str) -> Vec<String> {
    let mut out = vec![String::new()];
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '"' if quoted && chars.peek() == Some(&'"') => {
                chars.next();
                out.last_mut().unwrap().push('"');
            }
            '"' => quoted = !quoted,
            ',' if !quoted => out.push(String::new()),
            c => out.last_mut().unwrap().push(c),
        }
    }
    out
}

/// The rows of a CSV whose first line is `header`, as maps from column name
/// to field; every row has as many fields as the header.
pub fn csv_rows(text: &str, header: &str) -> Vec<HashMap<String, String>> {
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some(header));
    let names = csv_fields(header);
    lines
        .map(|line| {
            let fields = csv_fields(line);
            assert_eq!(fields.len(), names.len(), "{line}");
            names.iter().cloned().zip(fields).collect()
        })
        .collect()
}
