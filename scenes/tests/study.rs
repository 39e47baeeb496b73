//! `isochor study` end to end on coarse cantilevers: every run is recorded, the
//! reference is an extrapolation with an error estimate, errors are measured against it, and
//! the CSV, Markdown and PNG are written.

use isochor_scenes::study::{study, StudyRequest, LEVELS};
use isochor_scenes::Override;
use isochor_solvers::Method;

#[test]
fn cantilever_study_extrapolates_and_writes_its_outputs() {
    let dir = std::env::temp_dir().join(format!("isochor-study-test-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let request = StudyRequest {
        scene: "cantilever".into(),
        methods: vec![Method::Standard, Method::MixedP1],
        sweep: Some("res=2,3,4,6".into()),
        overrides: vec![Override::parse("steps=2").unwrap()],
        out: Some(dir.clone()),
        ..StudyRequest::default()
    };
    let (result, written) = study(&request).unwrap();
    assert_eq!(result.runs.len(), 8);
    assert_eq!(result.probe, "tip_deflection");
    let reference = result.reference.as_ref().expect("a reference");
    // Four runs: the estimate is the change of the extrapolation from the previous triple.
    let previous = reference.previous_gap.expect("four resolutions");
    assert_eq!(reference.estimate(), previous);
    assert!(reference.order > 0.0 && reference.limit > 0.0);
    for run in &result.runs {
        let value = run.value.expect("every run converges");
        let error = run.error.expect("measured against the reference");
        assert!((error - (value - reference.limit).abs() / reference.limit).abs() < 1e-12);
    }
    for level in LEVELS {
        assert_eq!(
            result.resolves(level),
            reference.relative_estimate() <= level
        );
    }
    let written = written.expect("an output folder");
    for file in ["study.csv", "study.md", "study.png"] {
        let len = std::fs::metadata(written.join(file)).unwrap().len();
        assert!(len > 0, "{file} is empty");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
