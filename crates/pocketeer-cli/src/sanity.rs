//! Is the job plausible for a milling machine? A drawing saved with the wrong unit header (a
//! plate drawn in millimetres under ezdxf's default of metres) pockets a thousand times too
//! large and runs for weeks; one drawn in inches under a millimetre header is smaller than the
//! tool. Neither is an error in the file, so the job goes on, but the user is told, with the
//! unit the drawing was read in and the `--units` that would read it otherwise.

use crate::display::JobUnits;
use pocketeer::geom::Aabb;
use pocketeer::import::Units;
use pocketeer::Analysis;

/// Larger than this (mm), in either direction, a pocket is not for a milling machine.
pub const LARGEST_POCKET: f64 = 3000.0;

/// Longer than this (seconds), a single pocketing job is most likely a unit mistake.
pub const LONGEST_JOB: f64 = 24.0 * 3600.0;

/// The extent of every pocket together (empty when there are none).
pub fn pockets_extent(a: &Analysis) -> Aabb {
    a.nesting
        .pockets
        .iter()
        .fold(Aabb::EMPTY, |b, p| b.union(&p.boundary.bbox()))
}

/// `W x H mm` of `b` (in `units`), with its corners.
pub fn describe_extent(b: &Aabb, units: JobUnits) -> String {
    if b.is_empty() {
        return "nothing".to_string();
    }
    let f = |v: f64| crate::display::fixed(v / units.mm(), 3);
    format!(
        "{} x {} {u}, from ({}, {}) to ({}, {})",
        f(b.width()),
        f(b.height()),
        f(b.min.x),
        f(b.min.y),
        f(b.max.x),
        f(b.max.y),
        u = units.symbol()
    )
}

/// How the drawing's unit came to be: declared, defaulted, or given with `--units`.
pub fn unit_origin(a: &Analysis) -> String {
    let d = &a.drawing;
    match d.declared_units {
        Some(declared) if declared == d.units => {
            format!("the drawing declares {} in $INSUNITS", declared.name())
        }
        Some(declared) => format!(
            "the drawing was read in {} as asked (--units), though it declares {}",
            d.units.name(),
            declared.name()
        ),
        None => format!("the drawing declares no unit and was read in {}", d.units.name()),
    }
}

/// What to try when the job looks `too_large` (or too small): the drawing's unit origin and
/// the `--units` that would read it a likelier size.
pub fn unit_advice(a: &Analysis, too_large: bool) -> String {
    let units = a.drawing.units;
    let other = if too_large {
        (units.mm() > 1.0).then_some(Units::Millimeters)
    } else if units.mm() < 25.4 {
        Some(Units::Inches)
    } else {
        None
    };
    match other {
        Some(o) => format!(
            "{}; if it is drawn in {}, pass --units {}",
            unit_origin(a),
            o.name(),
            o.symbol()
        ),
        None => format!("{}; check the drawing's unit (--units)", unit_origin(a)),
    }
}

/// Warnings about the size of the pockets, before anything is planned.
pub fn size_warnings(a: &Analysis) -> Vec<String> {
    let b = pockets_extent(a);
    if b.is_empty() || b.width().max(b.height()) <= LARGEST_POCKET {
        return Vec::new();
    }
    vec![format!(
        "the pockets span {:.0} x {:.0} mm ({:.1} m across): larger than any milling machine's table ({} m); {}",
        b.width(),
        b.height(),
        b.width().max(b.height()) / 1000.0,
        LARGEST_POCKET / 1000.0,
        unit_advice(a, true)
    )]
}

/// A warning when the job's estimated time is implausibly long.
pub fn time_warning(a: &Analysis, seconds: f64) -> Option<String> {
    (seconds > LONGEST_JOB).then(|| {
        format!(
            "the job is estimated at {} of machining, longer than {} h: {}",
            crate::display::time(seconds),
            LONGEST_JOB / 3600.0,
            unit_advice(a, true)
        )
    })
}
