//! Drawing units and their conversion to millimetres.

use serde::Serialize;
use std::fmt;
use std::str::FromStr;

/// A length unit a drawing can be in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Units {
    /// Millimetres.
    Millimeters,
    /// Centimetres.
    Centimeters,
    /// Decimetres.
    Decimeters,
    /// Metres.
    Meters,
    /// Micrometres.
    Microns,
    /// Inches.
    Inches,
    /// Feet.
    Feet,
    /// Thousandths of an inch.
    Mils,
    /// Millionths of an inch.
    Microinches,
    /// Yards.
    Yards,
}

impl Units {
    /// Millimetres per unit.
    pub fn mm(self) -> f64 {
        match self {
            Units::Millimeters => 1.0,
            Units::Centimeters => 10.0,
            Units::Decimeters => 100.0,
            Units::Meters => 1000.0,
            Units::Microns => 1e-3,
            Units::Inches => 25.4,
            Units::Feet => 304.8,
            Units::Mils => 0.0254,
            Units::Microinches => 25.4e-6,
            Units::Yards => 914.4,
        }
    }

    /// The unit of a DXF `$INSUNITS` code; `None` for unitless (0) and for units no part is
    /// drawn in (kilometres, light years, ...).
    pub fn from_insunits(code: i64) -> Option<Units> {
        Some(match code {
            1 => Units::Inches,
            2 => Units::Feet,
            4 => Units::Millimeters,
            5 => Units::Centimeters,
            6 => Units::Meters,
            8 => Units::Microinches,
            9 => Units::Mils,
            10 => Units::Yards,
            13 => Units::Microns,
            14 => Units::Decimeters,
            _ => return None,
        })
    }

    /// Short name (`mm`, `in`, ...).
    pub fn symbol(self) -> &'static str {
        match self {
            Units::Millimeters => "mm",
            Units::Centimeters => "cm",
            Units::Decimeters => "dm",
            Units::Meters => "m",
            Units::Microns => "um",
            Units::Inches => "in",
            Units::Feet => "ft",
            Units::Mils => "mil",
            Units::Microinches => "uin",
            Units::Yards => "yd",
        }
    }
}

impl Units {
    /// The unit's name in words (`millimetres`, `inches`, ...).
    pub fn name(self) -> &'static str {
        match self {
            Units::Millimeters => "millimetres",
            Units::Centimeters => "centimetres",
            Units::Decimeters => "decimetres",
            Units::Meters => "metres",
            Units::Microns => "micrometres",
            Units::Inches => "inches",
            Units::Feet => "feet",
            Units::Mils => "mils",
            Units::Microinches => "microinches",
            Units::Yards => "yards",
        }
    }
}

impl fmt::Display for Units {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.symbol())
    }
}

impl FromStr for Units {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Ok(match s.trim().to_ascii_lowercase().as_str() {
            "mm" | "millimeter" | "millimeters" | "millimetre" | "millimetres" => Units::Millimeters,
            "cm" => Units::Centimeters,
            "dm" => Units::Decimeters,
            "m" => Units::Meters,
            "um" | "micron" | "microns" => Units::Microns,
            "in" | "inch" | "inches" => Units::Inches,
            "ft" | "foot" | "feet" => Units::Feet,
            "mil" | "mils" | "thou" => Units::Mils,
            "yd" | "yard" | "yards" => Units::Yards,
            other => return Err(format!("unknown unit '{other}' (use mm, cm, m, in, ft, mil)")),
        })
    }
}
