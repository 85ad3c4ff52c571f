//! `pocketeer job JOB.toml`: the operations of a job file, each on its layers with its tool,
//! in one program with the tool changes between them.

use crate::display::{count, time, JobUnits};
use crate::jobfile::{self, JobFile, Locator, OperationKeys};
use crate::{output, Failure};
use clap::Args;
use pocketeer::import::{FillRule, Units};
use pocketeer::job::{Job, JobError, Operation, Tool};
use pocketeer::post::{write_gcode_tools, Coolant, Dialect, ProgramSettings, ProgramUnits};
use pocketeer::{Analysis, ImportOptions};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

#[derive(Args)]
pub struct JobArgs {
    /// The job file (TOML; `pocketeer job --print-template` writes a commented one).
    #[arg(required_unless_present = "print_template")]
    job: Option<PathBuf>,
    /// Write a commented template job file to standard output and stop.
    #[arg(long)]
    print_template: bool,
    /// Write the program here instead of to the job file's `output`.
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Also write an interactive preview: one self-contained HTML page.
    #[arg(long)]
    preview: Option<PathBuf>,
    /// Replay the program layer by layer before writing it (as `pocketeer check JOB PROGRAM`
    /// does) and refuse to write it when it gouges, leaves material or cuts too deep.
    #[arg(long)]
    check: bool,
}

/// A job file read and checked: the library's job, and what the program needs besides.
pub struct Loaded {
    pub job: Job,
    pub drawing: PathBuf,
    pub output: PathBuf,
    dialect: Dialect,
    coolant: Coolant,
    spindle_wait: f64,
    park: Option<pocketeer::geom::Point>,
    pub rapid_rate: f64,
    pub retract_time: f64,
    options: ImportOptions,
    /// Each operation's keys, `[defaults]` filled in (for messages that point at them).
    keys: Vec<OperationKeys>,
}

impl Loaded {
    /// A job made elsewhere than in a job file (from a drawing's layer names).
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        job: Job,
        drawing: PathBuf,
        output: PathBuf,
        dialect: Dialect,
        coolant: Coolant,
        spindle_wait: f64,
        rapid_rate: f64,
        retract_time: f64,
        options: ImportOptions,
    ) -> Loaded {
        let keys = vec![OperationKeys::default(); job.operations.len()];
        Loaded {
            job,
            drawing,
            output,
            dialect,
            coolant,
            spindle_wait,
            park: None,
            rapid_rate,
            retract_time,
            options,
            keys,
        }
    }

    /// Where to move at the end.
    pub fn with_park(mut self, park: Option<pocketeer::geom::Point>) -> Loaded {
        self.park = park;
        self
    }
}

/// The drawing read once per set of layers the operations name.
pub type Analyses = BTreeMap<Vec<String>, Analysis>;

/// Reads the job file at `path` and its drawing, every layer set once; `output` overrides the
/// file's output. Also returns the file's text, for messages that point into it.
pub fn read_job(path: &Path, output: Option<&PathBuf>) -> Result<(Loaded, Analyses, String), Failure> {
    let name = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| Failure(format!("{name}: cannot read: {e}")))?;
    let file = jobfile::parse(&name, &text).map_err(Failure)?;
    let loc = Locator {
        name: &name,
        text: &text,
    };
    let base = path.parent().unwrap_or(Path::new(""));
    let mut loaded = load(&file, &loc, base).map_err(Failure)?;
    if let Some(o) = output {
        loaded.output = o.clone();
    }
    let bytes = std::fs::read(&loaded.drawing)
        .map_err(|e| Failure(format!("{}: cannot read: {e}", loaded.drawing.display())))?;
    let analyses = analyses(Some(&loc), &loaded, &bytes)?;
    Ok((loaded, analyses, text))
}

pub fn run(args: &JobArgs) -> Result<(), Failure> {
    if args.print_template {
        return crate::emit(jobfile::TEMPLATE);
    }
    let Some(path) = &args.job else {
        return Err(Failure("a job file is needed (or --print-template)".into()));
    };
    let name = path.display().to_string();
    let (loaded, analyses, text) = read_job(path, args.output.as_ref())?;
    let mut outputs = vec![("output", loaded.output.as_path())];
    if let Some(p) = &args.preview {
        outputs.push(("--preview", p.as_path()));
    }
    output::guard(&[path, &loaded.drawing], &outputs).map_err(Failure)?;
    let loc = Locator {
        name: &name,
        text: &text,
    };
    let check = args.check.then_some(name.as_str());
    execute(&loaded, &analyses, path, args.preview.as_deref(), check, &|e| {
        located(&loc, &loaded, e)
    })
}

/// Runs a job read and checked (from a job file, or from a drawing's layer names) and writes
/// its program, and its preview when asked; `source` names it in the header and the title,
/// `locate` words the library's errors. With `check` (the job's name), the program is
/// replayed first and not written when the check fails.
pub fn execute(
    loaded: &Loaded,
    analyses: &Analyses,
    source: &Path,
    preview_page: Option<&Path>,
    check: Option<&str>,
    locate: &dyn Fn(&JobError) -> String,
) -> Result<(), Failure> {
    let path = source;
    let key = |layers: &[String]| layer_key(layers);
    let spinner = crate::progress::Spinner::start("planning");
    let results = pocketeer::job::run_job_with(
        &loaded.job,
        &|layers: &[String]| {
            analyses
                .get(&key(layers))
                .map(|a| (a.nesting.pockets.as_slice(), &a.tolerance))
        },
        &spinner,
    )
    .map_err(|e| Failure(locate(&e)))?;
    drop(spinner);
    for r in &results {
        let notes: Vec<String> = r
            .notes
            .iter()
            .map(|n| format!("operation {}: {n}", r.operation + 1))
            .collect();
        crate::print_warnings(&notes);
        let Some(p) = &r.pocketed else {
            if !loaded.job.operations[r.operation].rest {
                continue; // its note said why
            }
            eprintln!(
                "operation {}: nothing left to cut for tool {} ({} mm): no moves written",
                r.operation + 1,
                r.tool.number,
                crate::display::num(r.tool.diameter, 4)
            );
            continue;
        };
        let w: Vec<String> = (p.linked.warnings.iter().map(ToString::to_string))
            .chain(p.warnings.iter().map(ToString::to_string))
            .map(|w| format!("operation {}: {w}", r.operation + 1))
            .collect();
        crate::print_warnings(&w);
    }
    // The program: one section per operation, a tool change where the tool changes.
    let remarks: Vec<String> = results
        .iter()
        .map(|r| {
            let op = &loaded.job.operations[r.operation];
            let remark = format!(
                "operation {}: layers {}, depth {} mm, tool {}, {} mm{}",
                r.operation + 1,
                op.layers.join(", "),
                crate::display::num(op.link.depth, 4),
                r.tool.number,
                crate::display::num(r.tool.diameter, 4),
                if op.rest { ", rest" } else { "" }
            );
            short(&remark, REMARK_CHARS)
        })
        .collect();
    let mut sections = Vec::new();
    let mut loaded_tool = None;
    for (k, r) in results.iter().enumerate() {
        let change = loaded_tool != Some(r.tool.number);
        if let Some(section) = r.section(change, remarks[k].clone()) {
            sections.push(section);
            loaded_tool = Some(r.tool.number);
        }
    }
    let first = analyses.values().next();
    let units = first.map_or(JobUnits::Millimetres, |a| JobUnits::of(a.drawing.units));
    let safe_z = loaded
        .job
        .operations
        .iter()
        .map(|o| o.link.safe_z)
        .fold(0.0, f64::max);
    let mut header = vec![
        format!("pocketeer {}", env!("CARGO_PKG_VERSION")),
        format!(
            "{} {}",
            if is_toml(path) {
                "job"
            } else {
                "layer parameters of"
            },
            output::file_name(path)
        ),
        format!("drawing {}", output::file_name(&loaded.drawing)),
    ];
    header.extend(remarks.iter().cloned());
    let mut header: Vec<String> = header.iter().flat_map(|l| crate::display::wrap(l, 72)).collect();
    header.extend(crate::display::command_line_comment());
    let settings = ProgramSettings {
        units: match units {
            JobUnits::Millimetres => ProgramUnits::Millimetres,
            JobUnits::Inches => ProgramUnits::Inches,
        },
        safe_z,
        header,
        spindle_wait: loaded.spindle_wait,
        coolant: loaded.coolant,
        park: loaded.park,
        ..ProgramSettings::default()
    };
    let program = write_gcode_tools(&sections, &settings, loaded.dialect);
    let read = pocketeer::simulate::read_program(&program)
        .map_err(|e| Failure(format!("the program written does not read back: {e}")))?;
    if let Some(job) = check {
        let tolerances = (
            pocketeer::simulate::check::GOUGE_TOLERANCE,
            pocketeer::simulate::check::LEFTOVER_TOLERANCE,
        );
        let spinner = crate::progress::Spinner::start("checking the program");
        let (report, passed) = crate::check::job_report(loaded, analyses, job, &program, tolerances)?;
        drop(spinner);
        eprint!("{report}");
        if !passed {
            return Err(Failure(format!(
                "{job}: the check failed; {} not written",
                output::describe(&loaded.output)
            )));
        }
    }
    if let Some(page) = preview_page {
        let doc = preview(loaded, &results, analyses, &read, path)?;
        output::write_atomic(page, doc.as_bytes()).map_err(Failure)?;
    }
    output::write_output(&loaded.output, program.as_bytes()).map_err(Failure)?;
    let seconds: f64 = read.dwell
        + read
            .moves
            .iter()
            .map(|m| m.seconds(loaded.rapid_rate, loaded.retract_time))
            .sum::<f64>();
    let changes = sections.iter().skip(1).filter(|s| s.tool.is_some()).count();
    eprintln!(
        "{}, {}, {}: about {} (rapids at {}); written to {}",
        count(results.len(), "operation", "operations"),
        count(loaded.job.tools.len(), "tool", "tools"),
        count(changes, "tool change", "tool changes"),
        time(seconds),
        units.rate(loaded.rapid_rate),
        output::describe(&loaded.output)
    );
    Ok(())
}

/// A layer set as a map key: names in lower case, sorted.
/// Longest section remark, characters: with its parentheses within GRBL's 80 a line (long
/// layer names, as dxf2gcode's, are cut).
const REMARK_CHARS: usize = 72;

/// `s`, cut to `n` characters with "..." where it was longer.
fn short(s: &str, n: usize) -> String {
    if s.chars().count() <= n {
        return s.to_string();
    }
    let mut t: String = s.chars().take(n.saturating_sub(3)).collect();
    t.push_str("...");
    t
}

fn is_toml(p: &Path) -> bool {
    p.extension().is_some_and(|e| e.eq_ignore_ascii_case("toml"))
}

pub fn layer_key(layers: &[String]) -> Vec<String> {
    let mut k: Vec<String> = layers.iter().map(|l| l.to_lowercase()).collect();
    k.sort();
    k.dedup();
    k
}

/// The drawing read once for each set of layers the operations name; a layer the drawing
/// lacks is an error at the operation that names it.
pub fn analyses(
    loc: Option<&Locator>,
    loaded: &Loaded,
    bytes: &[u8],
) -> Result<BTreeMap<Vec<String>, Analysis>, Failure> {
    let drawing = loaded.drawing.display().to_string();
    // The drawing's layers, to name a missing one at the operation that asks for it.
    let all =
        pocketeer::read_drawing(bytes, &loaded.options).map_err(|e| Failure(format!("{drawing}: {e}")))?;
    let mut out = BTreeMap::new();
    for (k, op) in loaded.job.operations.iter().enumerate() {
        if let Some(layer) = op
            .layers
            .iter()
            .find(|l| !all.layers.iter().any(|d| d.eq_ignore_ascii_case(l)))
        {
            let what = format!(
                "layer '{layer}' is not in {} (its layers: {})",
                output::file_name(&loaded.drawing),
                all.layers.join(", ")
            );
            return Err(Failure(
                match (loc, loaded.keys.get(k).and_then(|o| o.layers.as_ref())) {
                    (Some(loc), Some(l)) => loc.at(l.span(), &format!("operations[{}].layers", k + 1), &what),
                    _ => what,
                },
            ));
        }
        let key = layer_key(&op.layers);
        if out.contains_key(&key) {
            continue;
        }
        let options = ImportOptions {
            layers: Some(op.layers.clone()),
            ..loaded.options.clone()
        };
        let a = pocketeer::analyze(bytes, &options).map_err(|e| Failure(format!("{drawing}: {e}")))?;
        crate::print_warnings(&crate::inspect::import_warnings(&a));
        out.insert(key, a);
    }
    Ok(out)
}

/// The library's job error, pointed at the key in the file where there is one.
fn located(loc: &Locator, loaded: &Loaded, e: &JobError) -> String {
    let span_of = |k: usize| loaded.keys.get(k).and_then(|o| o.tool.as_ref()).map(|t| t.span());
    match e {
        JobError::UnknownTool { operation, .. } => match span_of(*operation) {
            Some(s) => loc.at(s, &format!("operations[{}]", operation + 1), &e.to_string()),
            None => format!("{}: {e}", loc.name),
        },
        _ => format!("{}: {e}", loc.name),
    }
}

/// Reads the job file's keys into the library's job.
fn load(file: &JobFile, loc: &Locator, base: &Path) -> Result<Loaded, String> {
    let mut tools = Vec::new();
    for (k, t) in file.tools.iter().enumerate() {
        let key = |n: &str| format!("tools[{}].{n}", k + 1);
        tools.push(Tool {
            number: *t.number.get_ref(),
            diameter: loc.length(&t.diameter, &key("diameter"), true)?,
            feed: t
                .feed
                .as_ref()
                .map_or(Ok(1000.0), |f| loc.rate(f, &key("feed")))?,
            plunge_feed: t
                .plunge_feed
                .as_ref()
                .map_or(Ok(300.0), |f| loc.rate(f, &key("plunge-feed")))?,
            spindle: t.spindle.as_ref().map_or(12000.0, |s| *s.get_ref()),
        });
    }
    for (k, t) in tools.iter().enumerate() {
        if let Some(j) = tools[..k].iter().position(|o| o.number == t.number) {
            return Err(loc.at(
                file.tools[k].number.span(),
                &format!("tools[{}].number", k + 1),
                &format!("tool {} is numbered as tools[{}] is", t.number, j + 1),
            ));
        }
    }
    if file.operations.is_empty() {
        return Err(format!("{}: the job has no [[operations]]", loc.name));
    }
    let mut operations = Vec::new();
    let mut keys = Vec::new();
    for (k, raw) in file.operations.iter().enumerate() {
        let op = jobfile::with_defaults(raw, &file.defaults);
        let key = |n: &str| format!("operations[{}].{n}", k + 1);
        let layers = match &op.layers {
            Some(l) if !l.get_ref().is_empty() => l.get_ref().clone(),
            Some(l) => return Err(loc.at(l.span(), &key("layers"), "name at least one layer")),
            None => return Err(format!("{}: operation {} names no layers", loc.name, k + 1)),
        };
        let tool_key = op
            .tool
            .as_ref()
            .ok_or_else(|| format!("{}: operation {} names no tool", loc.name, k + 1))?;
        let number = *tool_key.get_ref();
        let tool = tools.iter().find(|t| t.number == number).ok_or_else(|| {
            let known: Vec<String> = tools.iter().map(|t| t.number.to_string()).collect();
            loc.at(
                tool_key.span(),
                &key("tool"),
                &format!(
                    "no tool {number} in [[tools]] (numbers: {})",
                    if known.is_empty() {
                        "none".to_string()
                    } else {
                        known.join(", ")
                    }
                ),
            )
        })?;
        let stepover = match &op.stepover {
            Some(q) => loc.stepover(q, tool.diameter)?,
            None => return Err(format!("{}: operation {} has no stepover", loc.name, k + 1)),
        };
        if stepover >= tool.diameter {
            return Err(loc.at(
                op.stepover.as_ref().map_or(0..0, |q| q.span()),
                &key("stepover"),
                "the stepover must be less than the tool's diameter",
            ));
        }
        let allowance = op
            .allowance
            .as_ref()
            .map_or(Ok(0.0), |q| loc.length(q, &key("allowance"), false))?;
        operations.push(Operation {
            layers,
            tool: number,
            stepover,
            allowance,
            link: jobfile::link_params(loc, k, &op, tool.diameter)?,
            rest: op.rest.unwrap_or(false),
        });
        keys.push(op);
    }
    let dialect = match file.post.as_ref() {
        None => Dialect::Grbl,
        Some(p) => match p.get_ref().to_ascii_lowercase().as_str() {
            "grbl" => Dialect::Grbl,
            "linuxcnc" => Dialect::LinuxCnc,
            "mach3" => Dialect::Mach3,
            other => return Err(loc.at(p.span(), "post", &format!("'{other}': grbl, linuxcnc or mach3"))),
        },
    };
    let coolant = match file.coolant.as_ref() {
        None => Coolant::Off,
        Some(c) => match c.get_ref().to_ascii_lowercase().as_str() {
            "off" => Coolant::Off,
            "flood" => Coolant::Flood,
            "mist" if dialect != Dialect::Grbl => Coolant::Mist,
            "mist" => {
                return Err(loc.at(
                    c.span(),
                    "coolant",
                    "GRBL 1.1's stock firmware has no M7; use flood",
                ))
            }
            other => return Err(loc.at(c.span(), "coolant", &format!("'{other}': off, flood or mist"))),
        },
    };
    let units = match file.units.as_ref() {
        None => None,
        Some(u) => Some(
            u.get_ref()
                .parse::<Units>()
                .map_err(|e| loc.at(u.span(), "units", &e))?,
        ),
    };
    let fill = match file.fill.as_ref() {
        None => FillRule::EvenOdd,
        Some(f) => match f.get_ref().to_ascii_lowercase().as_str() {
            "evenodd" => FillRule::EvenOdd,
            "nonzero" => FillRule::NonZero,
            other => return Err(loc.at(f.span(), "fill", &format!("'{other}': evenodd or nonzero"))),
        },
    };
    let options = ImportOptions {
        layers: None,
        units,
        join_tolerance: file
            .join_tolerance
            .as_ref()
            .map_or(Ok(0.001), |q| loc.length(q, "join-tolerance", false))?,
        close_gaps: file
            .close_gaps
            .as_ref()
            .map_or(Ok(0.05), |q| loc.length(q, "close-gaps", false))?,
        fill,
        strict: file.strict.unwrap_or(false),
        ignore_open: file.ignore_open.unwrap_or(false),
    };
    let output = match &file.output {
        Some(o) => base.join(o.get_ref()),
        None => base.join(Path::new(file.drawing.get_ref()).with_extension("nc")),
    };
    let spindle_wait = file.spindle_wait.as_ref().map_or(2.0, |w| *w.get_ref());
    if !(spindle_wait.is_finite() && spindle_wait >= 0.0) {
        return Err(loc.at(
            file.spindle_wait.as_ref().map_or(0..0, |w| w.span()),
            "spindle-wait",
            "a wait is zero seconds or more",
        ));
    }
    let park = match &file.park {
        None => None,
        Some(p) => {
            let (x, y) = crate::length::parse_point(p.get_ref()).map_err(|e| loc.at(p.span(), "park", &e))?;
            Some(pocketeer::geom::Point::new(x, y))
        }
    };
    Ok(Loaded {
        job: Job { tools, operations },
        drawing: base.join(file.drawing.get_ref()),
        output,
        dialect,
        coolant,
        spindle_wait,
        park,
        rapid_rate: file
            .rapid_rate
            .as_ref()
            .map_or(Ok(pocketeer::simulate::check::RAPID_RATE), |q| {
                loc.rate(q, "rapid-rate")
            })?,
        retract_time: file
            .retract_time
            .as_ref()
            .map_or(pocketeer::machining_time::DEFAULT_RETRACT_SECONDS, |t| {
                *t.get_ref()
            }),
        options,
        keys,
    })
}

/// The interactive page of the whole job: every layer's pockets, the program read back, the
/// tool changes.
fn preview(
    loaded: &Loaded,
    results: &[pocketeer::job::OperationResult],
    analyses: &BTreeMap<Vec<String>, Analysis>,
    read: &pocketeer::simulate::Program,
    path: &Path,
) -> Result<String, Failure> {
    // One analysis of all the operations' layers together, for the drawing shown.
    let mut all: Vec<String> = loaded
        .job
        .operations
        .iter()
        .flat_map(|o| o.layers.iter().cloned())
        .collect();
    all.sort();
    all.dedup();
    let bytes = std::fs::read(&loaded.drawing)
        .map_err(|e| Failure(format!("{}: cannot read: {e}", loaded.drawing.display())))?;
    let a = match analyses.get(&layer_key(&all)) {
        Some(a) => a.clone(),
        None => pocketeer::analyze(
            &bytes,
            &ImportOptions {
                layers: Some(all),
                ..loaded.options.clone()
            },
        )
        .map_err(|e| Failure(format!("{}: {e}", loaded.drawing.display())))?,
    };
    let diameter_of = |n: u32| {
        loaded
            .job
            .tools
            .iter()
            .find(|t| t.number == n)
            .map(|t| t.diameter)
    };
    let tool_changes: Vec<(usize, f64)> = read
        .tools
        .iter()
        .filter_map(|&(k, n)| diameter_of(n).map(|d| (k, d)))
        .collect();
    let first = results.first().map_or(0.0, |r| r.tool.diameter);
    let settings: Vec<(String, String)> = results
        .iter()
        .map(|r| {
            let op = &loaded.job.operations[r.operation];
            (
                format!("operation {}", r.operation + 1),
                format!(
                    "{}: tool {} ({} mm), depth {} mm, stepover {} mm, {}",
                    op.layers.join(", "),
                    r.tool.number,
                    crate::display::num(r.tool.diameter, 4),
                    crate::display::num(op.link.depth, 4),
                    crate::display::num(op.stepover, 4),
                    match &r.pocketed {
                        Some(p) => count(p.plans.iter().map(|p| p.loop_count()).sum(), "loop", "loops"),
                        None => "nothing left to cut".to_string(),
                    }
                ),
            )
        })
        .collect();
    let context = crate::page::Context {
        title: format!(
            "{} → {}",
            output::file_name(path),
            output::file_name(&loaded.output)
        ),
        tool_diameter: first,
        tool_changes,
        inches: JobUnits::of(a.drawing.units) == JobUnits::Inches,
        rapid_rate: loaded.rapid_rate,
        per_retract: loaded.retract_time,
        settings,
        too_narrow: Vec::new(),
        check: None,
        report: String::new(),
    };
    Ok(crate::page::html(&a, read, &context))
}
