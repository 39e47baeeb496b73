//! Checkpoints are validated as scene files are before `isochor resume` trusts them: each
//! field a run could not have written is refused, naming it. Before, each of these resumed
//! (to a wrong result, or a "converged" run at part of the load), panicked (`every = 0`) or
//! failed inside the solver, and a frame `../../x.vtu` reached the committed `frame.pvd`.

use crate::common::{isochor, scratch, stderr};
use std::path::Path;
use std::process::Output;
use toml::{Table, Value};

/// The checkpoint of a finished 4-step run, cut back to an interrupted run after 2 steps.
fn interrupted_checkpoint(dir: &Path) -> Table {
    let whole = dir.join("whole");
    let o = isochor(&[
        "run",
        "two-tets",
        "--set",
        "steps=4",
        "--checkpoint-every",
        "1",
        "--out",
        whole.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(whole.join("checkpoint.toml")).unwrap();
    let mut c: Table = text.parse().unwrap();
    c["finished"] = Value::Boolean(false);
    c["history"].as_array_mut().unwrap().truncate(2);
    c["frames"].as_array_mut().unwrap().truncate(3);
    let solver = c["solver"].as_table_mut().unwrap();
    for (key, value) in [
        ("steps", Value::Integer(2)),
        ("levels", Value::Integer(2)),
        ("t", Value::Float(0.5)),
        ("progress_t", Value::Float(0.5)),
    ] {
        solver[key] = value;
    }
    c
}

/// Resumes the run `name` of `dir` with the checkpoint `c`.
fn resume_with(dir: &Path, name: &str, c: &Table) -> Output {
    let temp = dir.join(format!(".{name}.tmp"));
    std::fs::create_dir_all(&temp).unwrap();
    std::fs::write(temp.join("checkpoint.toml"), toml::to_string(c).unwrap()).unwrap();
    isochor(&["resume", dir.join(name).to_str().unwrap()])
}

fn set(c: &mut Table, path: &[&str], value: Value) {
    let (last, parents) = path.split_last().unwrap();
    let mut t = c;
    for key in parents {
        t = t.get_mut(*key).unwrap().as_table_mut().unwrap();
    }
    t.insert(last.to_string(), value);
}

#[test]
fn corrupted_checkpoints_are_refused_naming_the_field() {
    let dir = scratch("checkpoints-fields");
    let base = interrupted_checkpoint(&dir);
    let o = resume_with(&dir, "baseline", &base);
    assert!(
        o.status.success(),
        "the unmodified checkpoint resumes: {}",
        stderr(&o)
    );
    let nan_position = {
        let mut c = base.clone();
        c["solver"]["positions"][0][0] = Value::Float(f64::NAN);
        c
    };
    let escaping_frame = {
        let mut c = base.clone();
        c["frames"][1][1] = Value::String("../../x.vtu".into());
        c
    };
    let dynamic = |dt: f64| {
        let mut c = base.clone();
        let mut stepping = Table::new();
        stepping.insert("mode".into(), Value::String("dynamic".into()));
        stepping.insert("dt".into(), Value::Float(dt));
        stepping.insert("frames".into(), Value::Integer(4));
        set(&mut c, &["scene", "stepping"], Value::Table(stepping));
        c
    };
    let mut cases: Vec<(&str, Table, &str)> = vec![
        ("nan-position", nan_position, "solver.positions"),
        ("escaping-frame", escaping_frame, "frames.1"),
        ("nan-dt", dynamic(f64::NAN), "stepping.dt"),
        ("negative-dt", dynamic(-1e-3), "stepping.dt"),
    ];
    let edits: [(&str, &[&str], Value, &str); 6] = [
        (
            "progress",
            &["solver", "progress_t"],
            Value::Float(5.0),
            "progress_t",
        ),
        (
            "levels",
            &["solver", "levels"],
            Value::Integer(1_000_000),
            "levels",
        ),
        (
            "steps-50",
            &["scene", "stepping", "steps"],
            Value::Integer(50),
            "progress_t",
        ),
        ("every", &["every"], Value::Integer(0), "every"),
        (
            "min-increment",
            &["scene", "stepping", "min_increment"],
            Value::Float(0.0),
            "min_increment",
        ),
        (
            "steps-0",
            &["scene", "stepping", "steps"],
            Value::Integer(0),
            "stepping.steps",
        ),
    ];
    for (name, path, value, key) in edits {
        let mut c = base.clone();
        set(&mut c, path, value);
        cases.push((name, c, key));
    }
    for (name, c, key) in &cases {
        let o = resume_with(&dir, name, c);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{name}: {err}");
        assert!(
            err.contains(key) && err.contains("checkpoint"),
            "{name}: {err}"
        );
        assert!(!err.contains("panicked"), "{name}: {err}");
        assert!(!dir.join(name).exists(), "{name}: committed");
        assert!(!dir.join("x.vtu").exists() && !Path::new("x.vtu").exists());
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
