//! The `isochor` command line (contract: docs/contracts.md).
//!
//! ```text
//! isochor list                                   # built-in scenes, one per line
//! isochor run SCENE [--set KEY=VALUE]... [--out DIR [--checkpoint-every N]] [--json] [--variant NAME]
//! isochor resume DIR [--json]                    # continue an interrupted checkpointed run
//! isochor compare SCENE --methods A,B,... [--set KEY=VALUE]... [--sweep KEY=V1,V2,...] [--out DIR] [--json]
//! isochor show SCENE [--set KEY=VALUE]... [--variant NAME]   # the scene as TOML, to copy and edit
//! isochor check SCENE [--set KEY=VALUE]... [--variant NAME] [--vtu FILE]  # validate, size selections and regions
//! isochor study SCENE --methods A,B,... [--elements tet4,tet10] [--sweep res=1,2,4,8] [--probe NAME]
//!               [--reference METHOD[/ELEMENT] | --reference-value VALUE [--reference-uncertainty REL]]
//!               [--max-unknowns N] [--set KEY=VALUE]... [--out DIR]
//! isochor penalties [--out DIR]                   # Fig. 3 of Sheen et al. 2021: U(J) and U'(J)
//! ```
//!
//! Exit status: 0 on success, 1 on an error (bad scene, key, value or file; nothing is
//! written), 2 on a command-line usage error, 3 when `run` completed but a step did not
//! converge (its outputs and JSON are still written, with `"converged": false`).

use crate::commands::check::check_scene;
use crate::commands::compare::{compare, describe_output, parse_methods, CompareRequest};
use crate::commands::penalties::write_penalty_plot;
use crate::commands::run::{resume_run, run_named};
use crate::commands::study::{parse_elements, study, ReferenceSpec, StudyRequest};
use crate::error::SceneError;
use crate::format::overrides::{check_conflicts, Override};
use crate::format::{builtin, SceneSource};
use crate::record::RunResult;
use clap::{Parser, Subcommand};
use std::io::Write;
use std::path::PathBuf;

/// Exit status of a run whose solver did not converge.
pub const EXIT_NOT_CONVERGED: i32 = 3;

/// Nearly incompressible soft solids on 4- or 10-node tets without locking.
#[derive(Debug, Parser)]
#[command(name = "isochor", version, about, long_about = None)]
pub struct Cli {
    /// The command to run.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// List the built-in scenes, one per line.
    List {
        /// Also print each scene's description and variants.
        #[arg(long)]
        long: bool,
    },
    /// Run a scene (a built-in name or a TOML file).
    Run {
        /// Built-in scene name or path to a TOML scene file.
        scene: String,
        /// Override a parameter: a flat name (nu, E, mu, rho, res, steps, method, mesh, ...)
        /// or a dotted key (material.nu, stepping.steps, ...).
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Apply one of the scene's named variants first.
        #[arg(long, value_name = "NAME")]
        variant: Option<String>,
        /// Write VTU frames, a .pvd, summary.json, CSV logs and PNG plots to this folder.
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Print exactly one JSON object on stdout.
        #[arg(long)]
        json: bool,
        /// Keep a restartable checkpoint in the output folder every N accepted steps (and at
        /// the end); `isochor resume DIR` continues an interrupted run from it.
        #[arg(long, value_name = "N", requires = "out")]
        checkpoint_every: Option<usize>,
    },
    /// Continue a run started with --checkpoint-every that was interrupted; the results equal
    /// the uninterrupted run's.
    Resume {
        /// The run's output folder (its --out).
        dir: PathBuf,
        /// Print exactly one JSON object on stdout.
        #[arg(long)]
        json: bool,
    },
    /// Run a scene with several methods (or variants) and print a table.
    Compare {
        /// Built-in scene name or path to a TOML scene file.
        scene: String,
        /// Methods to compare, comma-separated (e.g. standard,mixed-p1,zonal).
        #[arg(long, value_name = "A,B,...")]
        methods: Option<String>,
        /// Variants of the scene to compare, comma-separated (default without --methods: all).
        #[arg(long, value_name = "A,B,...")]
        variants: Option<String>,
        /// Override a parameter in every run.
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Repeat over the values of a parameter, e.g. nu=0.49,0.499,0.4999.
        #[arg(long, value_name = "KEY=V1,V2,...")]
        sweep: Option<String>,
        /// Write compare.csv, compare.md, compare.json, compare.png (with a numeric sweep),
        /// compare-residuals.png and, for dynamic scenes, compare-energy.png to this folder
        /// (default: compare-SCENE).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Print exactly one JSON object on stdout.
        #[arg(long)]
        json: bool,
    },
    /// Measure the speed/accuracy trade: every method on every element at every mesh
    /// resolution, the error of a probe against a reference (given, or Richardson-extrapolated),
    /// against wall time.
    Study {
        /// Built-in scene name or path to a TOML scene file.
        scene: String,
        /// Methods to compare, comma-separated (e.g. standard,mixed-p1,zonal).
        #[arg(long, value_name = "A,B,...")]
        methods: String,
        /// Elements to run every method on, comma-separated (tet4, tet10; default: the
        /// scene's element). Each (method, element) pair is a series, e.g. mixed-p1/tet10.
        #[arg(long, value_name = "E1,E2,...")]
        elements: Option<String>,
        /// Mesh resolutions (h = 1 / value), coarse to fine.
        #[arg(long, value_name = "KEY=V1,V2,...", default_value = "res=1,2,4,8")]
        sweep: String,
        /// The probe to measure (default: the scene's deflection probe).
        #[arg(long, value_name = "NAME")]
        probe: Option<String>,
        /// The series whose extrapolation is the reference, METHOD or METHOD/ELEMENT
        /// (default: the best-converging series).
        #[arg(long, value_name = "METHOD[/ELEMENT]")]
        reference: Option<String>,
        /// A reference value of the probe known from elsewhere (e.g. a converged computation),
        /// instead of an extrapolated one.
        #[arg(long, value_name = "VALUE", conflicts_with = "reference")]
        reference_value: Option<f64>,
        /// Relative uncertainty of --reference-value (0.003 for 0.3%; default 0: exact).
        /// Error levels finer than it are reported as not resolved.
        #[arg(long, value_name = "REL", requires = "reference_value")]
        reference_uncertainty: Option<f64>,
        /// Skip runs whose linear system would have more than N unknowns (and the finer runs
        /// of their series).
        #[arg(long, value_name = "N")]
        max_unknowns: Option<usize>,
        /// Override a parameter in every run.
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Write study.csv, study.md, study.png and study-unknowns.png to this folder (default:
        /// study-SCENE).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
    },
    /// Validate a scene without running it: print the size of each selection (vertices,
    /// faces, tets) and the volume of each region; optionally write a VTU showing them.
    Check {
        /// Built-in scene name or path to a TOML scene file.
        scene: String,
        /// Override a parameter.
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Apply one of the scene's named variants first.
        #[arg(long, value_name = "NAME")]
        variant: Option<String>,
        /// Write the rest mesh with a field per selection and the region of every tet.
        #[arg(long, value_name = "FILE")]
        vtu: Option<PathBuf>,
    },
    /// Plot the volumetric penalties U(J) and their stresses U'(J) over J in (0, 3] with
    /// lambda = 1 (Fig. 3 of Sheen et al. 2021): penalties.csv and penalties.png.
    Penalties {
        /// The folder to write to (default: penalties).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
    },
    /// Print a scene as TOML (after a variant and overrides), to copy, edit and run by path.
    Show {
        /// Built-in scene name or path to a TOML scene file.
        scene: String,
        /// Override a parameter.
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Apply one of the scene's named variants first.
        #[arg(long, value_name = "NAME")]
        variant: Option<String>,
    },
}

/// The `--set` overrides of a command line, each parameter set once.
fn parse_overrides(set: &[String]) -> Result<Vec<Override>, SceneError> {
    let overrides = set
        .iter()
        .map(|s| Override::parse(s))
        .collect::<Result<Vec<_>, _>>()?;
    check_conflicts(&overrides)?;
    Ok(overrides)
}

/// Runs a parsed command line, writing to `stdout`; returns the exit status.
pub fn execute(cli: Cli, stdout: &mut dyn Write) -> Result<i32, SceneError> {
    let io = SceneError::Stdout;
    match cli.command {
        Command::List { long } => {
            for name in builtin::names() {
                if long {
                    let scene = SceneSource::resolve(name)?.load(None, &[])?;
                    writeln!(stdout, "{name}\t{}", scene.description).map_err(io)?;
                    if !scene.variants.is_empty() {
                        let v: Vec<&str> = scene.variants.keys().map(String::as_str).collect();
                        writeln!(stdout, "\tvariants: {}", v.join(", ")).map_err(io)?;
                    }
                } else {
                    writeln!(stdout, "{name}").map_err(io)?;
                }
            }
            Ok(0)
        }
        Command::Penalties { out } => {
            let dir = write_penalty_plot(&out.unwrap_or_else(|| PathBuf::from("penalties")))?;
            writeln!(
                stdout,
                "wrote {} and {}",
                dir.join("penalties.csv").display(),
                dir.join("penalties.png").display()
            )
            .map_err(io)?;
            Ok(0)
        }
        Command::Show {
            scene,
            set,
            variant,
        } => {
            let overrides = parse_overrides(&set)?;
            let scene = SceneSource::resolve(&scene)?.load(variant.as_deref(), &overrides)?;
            write!(stdout, "{}", scene.to_toml_string()).map_err(io)?;
            Ok(0)
        }
        Command::Check {
            scene,
            set,
            variant,
            vtu,
        } => {
            let overrides = parse_overrides(&set)?;
            let scene = SceneSource::resolve(&scene)?.load(variant.as_deref(), &overrides)?;
            let report = check_scene(&scene, vtu.as_deref())?;
            write!(stdout, "{}", report.to_text()).map_err(io)?;
            if let Some(path) = vtu {
                writeln!(stdout, "wrote {}", path.display()).map_err(io)?;
            }
            Ok(0)
        }
        Command::Run {
            scene,
            set,
            variant,
            out,
            json,
            checkpoint_every,
        } => {
            let overrides = parse_overrides(&set)?;
            let (result, written) = run_named(
                &scene,
                variant.as_deref(),
                &overrides,
                out.as_deref(),
                !json,
                checkpoint_every,
            )?;
            report_run(&result, written, json, stdout)
        }
        Command::Resume { dir, json } => {
            let (result, written) = resume_run(&dir, !json)?;
            report_run(&result, written, json, stdout)
        }
        Command::Study {
            scene,
            methods,
            elements,
            sweep,
            probe,
            reference,
            reference_value,
            reference_uncertainty,
            max_unknowns,
            set,
            out,
        } => {
            let out = out.unwrap_or_else(|| default_out("study", &scene));
            let request = StudyRequest {
                scene,
                methods: parse_methods(&methods)?,
                elements: elements
                    .as_deref()
                    .map(parse_elements)
                    .transpose()?
                    .unwrap_or_default(),
                sweep: Some(sweep),
                probe,
                reference: match (reference, reference_value) {
                    (Some(series), _) => ReferenceSpec::parse_series(&series)?,
                    (None, Some(value)) => ReferenceSpec::Value {
                        value,
                        relative_uncertainty: reference_uncertainty.unwrap_or(0.0),
                    },
                    (None, None) => ReferenceSpec::Best,
                },
                max_unknowns,
                overrides: parse_overrides(&set)?,
                out: Some(out),
                progress: true,
            };
            let (result, written) = study(&request)?;
            write!(stdout, "{}", result.to_text()).map_err(io)?;
            if let Some(dir) = written {
                writeln!(
                    stdout,
                    "wrote {}, {}, {} and {}",
                    dir.join("study.csv").display(),
                    dir.join("study.md").display(),
                    dir.join("study.png").display(),
                    dir.join("study-unknowns.png").display()
                )
                .map_err(io)?;
            }
            Ok(0)
        }
        Command::Compare {
            scene,
            methods,
            variants,
            set,
            sweep,
            out,
            json,
        } => {
            let out = out.unwrap_or_else(|| default_out("compare", &scene));
            let request = CompareRequest {
                scene,
                methods: methods
                    .as_deref()
                    .map(parse_methods)
                    .transpose()?
                    .unwrap_or_default(),
                variants: variants
                    .map(|v| {
                        v.split(',')
                            .map(|s| s.trim().to_string())
                            .filter(|s| !s.is_empty())
                            .collect()
                    })
                    .unwrap_or_default(),
                overrides: parse_overrides(&set)?,
                sweep,
                out: Some(out),
                progress: !json,
            };
            let (comparison, written) = compare(&request)?;
            if json {
                let text = serde_json::to_string(&comparison.to_json())
                    .map_err(|e| SceneError::Output(e.to_string()))?;
                writeln!(stdout, "{text}").map_err(io)?;
            } else {
                write!(stdout, "{}", comparison.to_text()).map_err(io)?;
                if let Some(dir) = written {
                    writeln!(stdout, "{}", describe_output(&dir)).map_err(io)?;
                }
            }
            Ok(0)
        }
    }
}

/// The output folder of a command without `--out`: `COMMAND-SCENE` (the scene file's stem).
fn default_out(command: &str, scene: &str) -> PathBuf {
    let stem = std::path::Path::new(scene)
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| scene.to_string());
    PathBuf::from(format!("{command}-{stem}"))
}

/// Prints a run's result (JSON or the summary for people); returns the exit status.
fn report_run(
    result: &RunResult,
    written: Option<PathBuf>,
    json: bool,
    stdout: &mut dyn Write,
) -> Result<i32, SceneError> {
    let io = SceneError::Stdout;
    if json {
        let text = serde_json::to_string(&result.to_json())
            .map_err(|e| SceneError::Output(e.to_string()))?;
        writeln!(stdout, "{text}").map_err(io)?;
    } else {
        write!(stdout, "{}", human_summary(result)).map_err(io)?;
        if let Some(dir) = written {
            writeln!(stdout, "outputs: {}", dir.display()).map_err(io)?;
        }
    }
    Ok(if result.converged {
        0
    } else {
        EXIT_NOT_CONVERGED
    })
}

/// A run's summary for people.
pub fn human_summary(r: &RunResult) -> String {
    let mut s = String::new();
    let variant = r
        .variant
        .as_deref()
        .map(|v| format!(" [{v}]"))
        .unwrap_or_default();
    s += &format!("scene              {}{variant}\n", r.scene);
    s += &format!("method             {} (nu = {})\n", r.method, r.nu);
    s += &format!(
        "mesh               {} vertices, {} tets, {} unknowns\n",
        r.vertices, r.tets, r.dofs
    );
    s += &format!(
        "steps              {} accepted, {} cut, for {} frames\n",
        r.steps, r.cuts, r.steps_requested
    );
    s += &format!("newton iterations  {}\n", r.newton_iterations);
    s += &format!(
        "converged          {}\n",
        if r.converged { "yes" } else { "no" }
    );
    if let Some(e) = &r.error {
        s += &format!("stopped at step {}: {e}\n", r.failed_step.unwrap_or(0));
    }
    s += &format!("wall time          {:.3} s\n", r.wall_time_s);
    s += &format!("volume change      {:+.4e} %\n", 100.0 * r.volume_change);
    s += &format!("max inverted tets  {}\n", r.max_inverted_tets);
    for (name, value) in &r.probes {
        s += &format!("{name:<18} {value:.6e}\n");
    }
    s
}
