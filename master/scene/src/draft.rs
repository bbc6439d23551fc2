//! A scene file read once, and the changes made to it before it is checked
//! (`slender run --set`, a study's `--vary`, a fidelity study's choices).
//!
//! The file's text is parsed once into its keys with their spans. A change is
//! made on a plain copy of the keys (a `toml::Table`, what the commands know
//! how to edit) and recorded as the key paths it changed, each marked with
//! what made it (`--set master.scheme=jacobi`). The scene is typed from the
//! spanned keys with the changed values put in: no TOML text is written and
//! read back, so an error about a key the user wrote names the user's line,
//! and one about a changed value names the change.

use crate::{Scene, SceneError};
use std::borrow::Cow;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use toml::de::{DeArray, DeTable, DeValue};
use toml::{Spanned, Table, Value};

/// Scene texts parsed in this process (`texts_parsed`).
static TEXTS_PARSED: AtomicUsize = AtomicUsize::new(0);

/// How many scene texts this process has parsed: what a test counts to show
/// that a study reads the user's file once and writes no text to read again.
pub fn texts_parsed() -> usize {
    TEXTS_PARSED.load(Ordering::Relaxed)
}

/// One step of a key path: a table's key or an array's index.
#[derive(Clone, Debug, PartialEq)]
enum Part {
    Key(String),
    Index(usize),
}

/// A scene's keys spanned in its text.
type SpannedKeys<'a> = Spanned<DeTable<'a>>;

self_cell::self_cell!(
    /// A scene's text and its keys as read, spanned in it.
    struct Keys {
        owner: String,
        #[covariant]
        dependent: SpannedKeys,
    }
);

/// A scene file's keys as read, with their spans, and the changes made to
/// them (see the module's doc). A copy shares the text and its keys.
#[derive(Clone)]
pub struct Draft {
    path: PathBuf,
    /// The file's text and its keys as read.
    keys: Arc<Keys>,
    /// The keys with the changes made so far.
    table: Table,
    /// What made each change, in order (`--set KEY=VALUE`).
    origins: Vec<String>,
    /// The key paths each change set or removed, with its index in `origins`.
    changed: Vec<(Vec<Part>, usize)>,
}

impl Draft {
    /// Reads the scene file at `path`.
    pub fn read(path: &Path) -> Result<Draft, SceneError> {
        let source = std::fs::read_to_string(path).map_err(|e| SceneError {
            file: path.to_owned(),
            line: None,
            key: String::new(),
            message: format!("cannot read the file: {e}"),
        })?;
        Draft::parse(path, source)
    }

    /// Reads the scene text `source` of the file `path` (named in errors).
    pub fn parse(path: &Path, source: String) -> Result<Draft, SceneError> {
        TEXTS_PARSED.fetch_add(1, Ordering::Relaxed);
        let error = |source: &str, e: toml::de::Error| SceneError {
            file: path.to_owned(),
            line: e.span().map(|s| crate::line_of(source, s.start)),
            key: String::new(),
            message: e.message().trim().to_owned(),
        };
        let keys = Keys::try_new_or_recover(source, |text| DeTable::parse(text))
            .map_err(|(source, e)| error(&source, e))?;
        let deserializer = toml::de::Deserializer::from(keys.borrow_dependent().clone());
        let table = serde::Deserialize::deserialize(deserializer)
            .map_err(|e| error(keys.borrow_owner(), e))?;
        Ok(Draft {
            path: path.to_owned(),
            keys: Arc::new(keys),
            table,
            origins: Vec::new(),
            changed: Vec::new(),
        })
    }

    /// The scene's keys with the changes made so far, to read and to copy
    /// for a change.
    pub fn table(&self) -> &Table {
        &self.table
    }

    /// Whether any change was made.
    pub fn is_changed(&self) -> bool {
        !self.origins.is_empty()
    }

    /// Makes `table` the scene's keys, the values that differ from the
    /// present ones marked as changed by `origin` (e.g. `--set
    /// simulation.step=0.1`, named by an error about them).
    pub fn change(&mut self, origin: impl Into<String>, table: Table) {
        let k = self.origins.len();
        let mut paths = Vec::new();
        differences(&self.table, &table, &mut Vec::new(), &mut paths);
        self.changed.extend(paths.into_iter().map(|p| (p, k)));
        self.origins.push(origin.into());
        self.table = table;
    }

    /// Changes the keys by `edit`, marked with `origin`; an error of `edit`
    /// leaves the draft as it was.
    pub fn edit<E>(
        &mut self,
        origin: impl Into<String>,
        edit: impl FnOnce(&mut Table) -> Result<(), E>,
    ) -> Result<(), E> {
        let mut table = self.table.clone();
        edit(&mut table)?;
        self.change(origin, table);
        Ok(())
    }

    /// The scene, typed from the file's spanned keys with the changes put
    /// in, checked and built once (as `Scene::parse`).
    pub fn scene(&self) -> Result<Scene, SceneError> {
        let values: Vec<Option<&Value>> = (self.changed.iter())
            .map(|(path, _)| value_at(&self.table, path))
            .collect();
        // toml's integers and floats are made only from their text: each
        // changed number's, written here and read at once.
        let mut numbers = Vec::new();
        values
            .iter()
            .flatten()
            .for_each(|v| number_texts(v, &mut numbers));
        let mut numbers = numbers.iter();
        let source = self.keys.borrow_owner();
        let mut document = self.keys.borrow_dependent().clone();
        for ((path, k), value) in self.changed.iter().zip(&values) {
            let mark = mark(source, *k);
            let value = value.map(|v| spanned(v, &mark, &mut numbers));
            put(document.get_mut(), path, value, &mark);
        }
        let changes = Changes {
            origins: self.origins.clone(),
            // Each path as errors may name it: by index, and by name where
            // an array's items have names.
            keys: (self.changed.iter())
                .flat_map(|(path, k)| {
                    let named = named_path(&self.table, path);
                    let by_name = (named != *path).then(|| (dotted(&named), *k));
                    std::iter::once((dotted(path), *k)).chain(by_name)
                })
                .collect(),
            table: self.is_changed().then(|| self.table.clone()),
        };
        Scene::from_document(&self.path, source, document, changes)
    }
}

/// The changes a scene was made with, for its errors and its expansion.
#[derive(Debug, Default)]
pub(crate) struct Changes {
    /// What made each change (`--set KEY=VALUE`).
    pub origins: Vec<String>,
    /// The key paths changed (`units[2].parameters.elements`), each with its
    /// change's index in `origins`.
    pub keys: Vec<(String, usize)>,
    /// The scene's keys as changed; None for the file as written.
    pub table: Option<Table>,
}

impl Changes {
    /// What made the changes to `key` (a key path as errors name it, e.g.
    /// `master` or `units[1] ("pipe").parameters`): those that changed a
    /// key below it or above it.
    pub(crate) fn origins_of(&self, key: &str) -> Vec<&str> {
        let key = key.split(' ').next().unwrap_or(key);
        let within = |outer: &str, inner: &str| {
            inner == outer
                || (inner.starts_with(outer)
                    && matches!(inner.as_bytes().get(outer.len()), Some(b'.' | b'[')))
        };
        let mut found: Vec<&str> = Vec::new();
        for (changed, k) in &self.keys {
            let origin = self.origins[*k].as_str();
            if !key.is_empty()
                && (within(key, changed) || within(changed, key))
                && !found.contains(&origin)
            {
                found.push(origin);
            }
        }
        found
    }
}

impl Changes {
    /// `e`, about the key `about`, saying which changes made the keys it is
    /// about, or (when it names none of them) every change made.
    pub(crate) fn name_in(&self, mut e: SceneError, about: &str) -> SceneError {
        let mut origins = self.origins_of(about);
        if origins.is_empty() {
            origins = self.origins.iter().map(String::as_str).collect();
        }
        if !origins.is_empty() && !e.message.contains(CHANGED_BY) {
            e.message = format!("{} ({CHANGED_BY} {})", e.message, origins.join(", "));
        }
        e
    }
}

/// How an error names the changes behind the keys it is about.
pub(crate) const CHANGED_BY: &str = "the scene as changed by";

/// `path` with each array index whose item in `table` has a `name` written
/// as that name (`structure.sections.laid`, as the structure's errors name
/// a section).
fn named_path(table: &Table, path: &[Part]) -> Vec<Part> {
    let mut named = Vec::with_capacity(path.len());
    for (k, part) in path.iter().enumerate() {
        let name = match part {
            Part::Index(_) => value_at(table, &path[..=k])
                .and_then(|item| item.get("name"))
                .and_then(Value::as_str),
            Part::Key(_) => None,
        };
        named.push(name.map_or_else(|| part.clone(), |n| Part::Key(n.to_owned())));
    }
    named
}

/// A key path as errors name it: `units[2].parameters.elements`.
fn dotted(path: &[Part]) -> String {
    let mut text = String::new();
    for part in path {
        match part {
            Part::Key(key) if text.is_empty() => text.push_str(key),
            Part::Key(key) => {
                text.push('.');
                text.push_str(key);
            }
            Part::Index(k) => text.push_str(&format!("[{k}]")),
        }
    }
    text
}

/// The span that marks values changed by change `k` of a scene whose text
/// is `source`: past its end, one byte a change (`origin_of` reads it back).
fn mark(source: &str, k: usize) -> Range<usize> {
    let at = source.len() + 1 + k;
    at..at + 1
}

/// The change (its index) whose mark `span` is, None for a span in `source`.
pub(crate) fn origin_of(source: &str, span: &Range<usize>) -> Option<usize> {
    span.start.checked_sub(source.len() + 1)
}

/// The topmost key paths below `path` where `after` differs from `before`.
fn differences(before: &Table, after: &Table, path: &mut Vec<Part>, out: &mut Vec<Vec<Part>>) {
    let keys = before
        .keys()
        .chain(after.keys().filter(|k| !before.contains_key(*k)));
    for key in keys {
        path.push(Part::Key(key.clone()));
        match (before.get(key), after.get(key)) {
            (Some(b), Some(a)) => value_differences(b, a, path, out),
            _ => out.push(path.clone()),
        }
        path.pop();
    }
}

fn value_differences(
    before: &Value,
    after: &Value,
    path: &mut Vec<Part>,
    out: &mut Vec<Vec<Part>>,
) {
    if before == after {
        return;
    }
    match (before, after) {
        (Value::Table(b), Value::Table(a)) => differences(b, a, path, out),
        (Value::Array(b), Value::Array(a)) if b.len() == a.len() => {
            for (k, (b, a)) in b.iter().zip(a).enumerate() {
                path.push(Part::Index(k));
                value_differences(b, a, path, out);
                path.pop();
            }
        }
        _ => out.push(path.clone()),
    }
}

/// The value at `path` in `table`, if there is one.
fn value_at<'t>(table: &'t Table, path: &[Part]) -> Option<&'t Value> {
    let (first, rest) = path.split_first()?;
    let Part::Key(key) = first else { return None };
    rest.iter()
        .try_fold(table.get(key)?, |here, part| match part {
            Part::Key(key) => here.get(key),
            Part::Index(k) => here.get(*k),
        })
}

/// The text of every number in `value`, in the order `spanned` reads them.
fn number_texts(value: &Value, out: &mut Vec<String>) {
    match value {
        Value::Integer(_) | Value::Float(_) => out.push(value.to_string()),
        Value::Array(items) => items.iter().for_each(|v| number_texts(v, out)),
        Value::Table(t) => t.values().for_each(|v| number_texts(v, out)),
        Value::String(_) | Value::Boolean(_) | Value::Datetime(_) => {}
    }
}

/// `value` as a spanned TOML value, every part spanned at `mark`; its
/// numbers read from `numbers` (`number_texts`).
fn spanned<'n>(
    value: &Value,
    mark: &Range<usize>,
    numbers: &mut impl Iterator<Item = &'n String>,
) -> Spanned<DeValue<'n>> {
    let at = |v| Spanned::new(mark.clone(), v);
    match value {
        Value::String(s) => at(DeValue::String(Cow::Owned(s.clone()))),
        Value::Boolean(b) => at(DeValue::Boolean(*b)),
        Value::Datetime(d) => at(DeValue::Datetime(*d)),
        Value::Integer(_) | Value::Float(_) => {
            // A number's own text (`Value`'s display) reads back as it; were
            // it not to, the text stays a string that the scene refuses.
            let text = numbers.next().map_or("", String::as_str);
            let read = DeValue::parse(text).map(Spanned::into_inner);
            at(read.unwrap_or_else(|_| DeValue::String(Cow::Owned(text.to_owned()))))
        }
        Value::Array(items) => {
            let mut array = DeArray::new();
            items
                .iter()
                .for_each(|v| array.push(spanned(v, mark, numbers)));
            at(DeValue::Array(array))
        }
        Value::Table(t) => {
            let mut table = DeTable::new();
            for (key, v) in t {
                let key = Spanned::new(mark.clone(), Cow::Owned(key.clone()));
                table.insert(key, spanned(v, mark, numbers));
            }
            at(DeValue::Table(table))
        }
    }
}

/// Puts `value` at `path` of `table` (removes what is there for None),
/// making missing tables on the way, spanned at `mark`.
fn put<'n>(
    table: &mut DeTable<'n>,
    path: &[Part],
    value: Option<Spanned<DeValue<'n>>>,
    mark: &Range<usize>,
) {
    let Some((Part::Key(key), rest)) = path.split_first() else {
        return;
    };
    if rest.is_empty() {
        match value {
            Some(v) => {
                table.insert(Spanned::new(mark.clone(), Cow::Owned(key.clone())), v);
            }
            None => {
                table.remove(key.as_str());
            }
        }
        return;
    }
    let child = table
        .entry(Spanned::new(mark.clone(), Cow::Owned(key.clone())))
        .or_insert_with(|| Spanned::new(mark.clone(), DeValue::Table(DeTable::new())));
    put_in(child.get_mut(), rest, value, mark);
}

/// `put` below a value: a table's key or an array's item.
fn put_in<'n>(
    here: &mut DeValue<'n>,
    path: &[Part],
    value: Option<Spanned<DeValue<'n>>>,
    mark: &Range<usize>,
) {
    match (here, path.split_first()) {
        (DeValue::Table(t), Some((Part::Key(_), _))) => put(t, path, value, mark),
        (DeValue::Array(items), Some((Part::Index(k), rest))) => {
            let Some(item) = items.get_mut(*k) else {
                return;
            };
            match (rest.is_empty(), value) {
                (true, Some(v)) => *item = v,
                (true, None) => {}
                (false, value) => put_in(item.get_mut(), rest, value, mark),
            }
        }
        _ => {}
    }
}

#[cfg(test)]
mod tests;
