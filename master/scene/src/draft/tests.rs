//! A draft's changes: typed from the spanned keys, no text written, errors
//! at the user's line or naming the change.

use super::Draft;
use crate::tests::{HANGING_PIPE, line_of};
use std::path::Path;

fn draft(text: &str) -> Draft {
    Draft::parse(Path::new("pipe.toml"), text.to_owned()).expect("the scene's text")
}

#[test]
fn a_change_reaches_the_typed_scene() {
    let mut d = draft(HANGING_PIPE);
    d.edit("--set simulation.duration=2", |t| {
        t["simulation"]["duration"] = toml::Value::Float(2.0);
        Ok::<(), &str>(())
    })
    .expect("the edit");
    let scene = d.scene().expect("the scene");
    assert_eq!(scene.spec.simulation.duration, 2.0);
    // The expansion is of the changed keys.
    let text = scene.source().expect("the expansion");
    let table: toml::Table = toml::from_str(text).expect("TOML");
    assert_eq!(table["simulation"]["duration"].as_float(), Some(2.0));
}

#[test]
fn an_error_about_a_key_the_user_wrote_names_its_line() {
    // A change elsewhere does not lose the user's lines.
    let text = HANGING_PIPE.replacen(
        "[[structure.sections]]",
        "[[structure.sections]]\nelemnts = 10",
        1,
    );
    let mut d = draft(&text);
    d.edit("--set simulation.duration=2", |t| {
        t["simulation"]["duration"] = toml::Value::Float(2.0);
        Ok::<(), &str>(())
    })
    .expect("the edit");
    let error = d.scene().expect_err("an unknown key").to_string();
    let line = line_of(&text, "elemnts");
    assert!(error.starts_with(&format!("pipe.toml:{line}:")), "{error}");
}

#[test]
fn an_error_about_a_changed_value_names_the_change() {
    let mut d = draft(HANGING_PIPE);
    d.edit("--set simulation.step=fast", |t| {
        t["simulation"]["step"] = toml::Value::String("fast".into());
        Ok::<(), &str>(())
    })
    .expect("the edit");
    let error = d.scene().expect_err("a string step").to_string();
    assert!(
        error.starts_with("pipe.toml: `simulation.step`: --set simulation.step=fast: "),
        "{error}"
    );
    // A value built into a unit: the unit's error names the change too.
    let mut d = draft(HANGING_PIPE);
    d.edit("--vary master.tolerances.velocity=-1", |t| {
        t["master"]["tolerances"]["velocity"] = toml::Value::Float(-1.0);
        Ok::<(), &str>(())
    })
    .expect("the edit");
    let error = d.scene().expect_err("a negative tolerance").to_string();
    assert!(
        error.ends_with("(the scene as changed by --vary master.tolerances.velocity=-1)"),
        "{error}"
    );
}

#[test]
fn a_removed_key_and_a_new_table_are_typed_as_changed() {
    let mut d = draft(HANGING_PIPE);
    d.edit("remove the twin", |t| {
        let s = t["structure"].as_table_mut().ok_or("no structure")?;
        s.remove("reference");
        t.remove("output");
        Ok::<(), &str>(())
    })
    .expect("the edit");
    let with = draft(HANGING_PIPE)
        .scene()
        .expect("the scene")
        .spec
        .units
        .len();
    assert_eq!(d.scene().expect("the scene").spec.units.len(), with - 1);
    d.edit("--set master.acceleration.kind=aitken", |t| {
        let m = t["master"].as_table_mut().ok_or("no master")?;
        m.insert(
            "acceleration".into(),
            toml::toml! { kind = "aitken" }.into(),
        );
        Ok::<(), &str>(())
    })
    .expect("the edit");
    d.scene().expect("the scene with an acceleration");
}

#[test]
fn an_edit_that_fails_leaves_the_draft_as_it_was() {
    let mut d = draft(HANGING_PIPE);
    let error = d.edit("--set x=1", |_| Err("no such key"));
    assert_eq!(error, Err("no such key"));
    assert!(!d.is_changed());
}
