//! Boards as data: one TOML file per board under `boards/` (compiled into the
//! tool). Their pin files (Xilinx ISE UCF, iCE40 PCF, ECP5 LPF, Vivado XDC) are
//! written by `rust-hdl-fpga-support` ([`pinfile`], through the board top of
//! [`top`]).
//!
//! A board maps *roles* to pins. A role is one bit of a design's top-level
//! port, written `name` for a 1-bit port and `name[i]` for bit i of a vector.
//! Designs list the roles they need (functional) and the debug outputs they
//! would like placed; the writer fails if a functional role has no pin,
//! places debug bits on the board's debug pins in order and reports the rest.

use anyhow::{anyhow, bail, Context, Result};
use serde::Deserialize;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

pub mod pinfile;
pub mod top;


/// Pin-file format of a board.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Format {
    /// Xilinx ISE user constraints file.
    Ucf,
    /// iCE40 physical constraints file (nextpnr-ice40).
    Pcf,
    /// Lattice preference file (ECP5, nextpnr-ecp5).
    Lpf,
    /// Xilinx design constraints (Vivado).
    Xdc,
}

impl Format {
    /// File extension of the format's pin files.
    pub fn ext(self) -> &'static str {
        match self {
            Format::Ucf => "ucf",
            Format::Pcf => "pcf",
            Format::Lpf => "lpf",
            Format::Xdc => "xdc",
        }
    }

    /// The tool flow that reads the format.
    pub fn tool(self) -> &'static str {
        match self {
            Format::Ucf => "Xilinx ISE",
            Format::Pcf => "nextpnr-ice40",
            Format::Lpf => "nextpnr-ecp5 / Diamond",
            Format::Xdc => "Vivado",
        }
    }
}

#[derive(Debug, Clone, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ClockPin {
    /// Top-level clock port name.
    pub port: String,
    pub pin: String,
    /// Oscillator frequency.
    pub hz: u64,
}

#[derive(Debug, Clone, PartialEq, Eq, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DebugPins {
    pub pins: Vec<String>,
}

/// A board description.
#[derive(Debug, Clone, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Board {
    pub name: String,
    pub description: String,
    /// FPGA family (`spartan3`, `ice40`, `ecp5`, `artix7`).
    pub family: String,
    pub part: String,
    #[serde(default)]
    pub package: Option<String>,
    pub format: Format,
    #[serde(default)]
    pub iostandard: Option<String>,
    pub clock: ClockPin,
    /// Pins of the hub's port bits (the published hub pin map on the XSA board).
    pub pins: BTreeMap<String, String>,
    #[serde(default)]
    pub debug: DebugPins,
    /// Pinout of the controller designs on the same board (optional): a
    /// different bitstream, so its pins may reuse the hub's.
    #[serde(default)]
    pub controller: Option<ControllerPins>,
    /// Pinout of the USB-to-CAN adapter (`slcan`, board top `canstar_slcan_board`:
    /// `rst_n`, `uart_rx`, `uart_tx`, `rx`, `tx`), optional like the controller's.
    #[serde(default)]
    pub slcan: Option<ControllerPins>,
    /// The file the board was read from (for messages; not a key of the file).
    #[serde(skip)]
    pub source: Option<String>,
}

/// The pinout of one design other than the hub (`[controller.pins]`, `[slcan.pins]`).
#[derive(Debug, Clone, PartialEq, Eq, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ControllerPins {
    /// Role (port bit of the controller's board top) -> pin.
    pub pins: BTreeMap<String, String>,
}

/// Which of a board's pinouts a design uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pinout {
    /// `[pins]` and `[debug]`: the hub.
    Hub,
    /// `[controller.pins]`; debug outputs go to the debug pins it leaves free.
    Controller,
    /// `[slcan.pins]`; debug outputs go to the debug pins it leaves free.
    Slcan,
}

impl Pinout {
    /// The board file's table of this pinout (for messages).
    pub fn table(self) -> &'static str {
        match self {
            Pinout::Hub => "pins",
            Pinout::Controller => "controller.pins",
            Pinout::Slcan => "slcan.pins",
        }
    }
}

/// The boards shipped with canstar.
pub const BUILTIN: &[(&str, &str)] = &[
    ("xsa-3s1000", include_str!("../boards/xsa-3s1000.toml")),
    ("ice40-hx8k", include_str!("../boards/ice40-hx8k.toml")),
    ("alchitry-cu", include_str!("../boards/alchitry-cu.toml")),
    ("ulx3s", include_str!("../boards/ulx3s.toml")),
    ("arty-a7", include_str!("../boards/arty-a7.toml")),
];

impl Board {
    /// Parse and check a board description.
    pub fn from_toml(text: &str) -> Result<Self> {
        let b: Board = toml::from_str(text).map_err(|e| anyhow!("malformed board file: {e}"))?;
        b.validate()?;
        Ok(b)
    }

    /// A built-in board by name, or a board file given by path.
    pub fn lookup(name_or_path: &str) -> Result<Self> {
        if let Some((_, text)) = BUILTIN.iter().find(|(n, _)| *n == name_or_path) {
            return Self::from_toml(text).with_context(|| format!("built-in board {name_or_path}"));
        }
        if name_or_path.ends_with(".toml") && Path::new(name_or_path).exists() {
            let text = crate::input::read_toml(Path::new(name_or_path))?;
            let mut b = Self::from_toml(&text).map_err(|e| anyhow!("{name_or_path}: {e:#}"))?;
            b.source = Some(name_or_path.to_string());
            return Ok(b);
        }
        let known: Vec<&str> = BUILTIN.iter().map(|(n, _)| *n).collect();
        bail!("unknown board `{name_or_path}` (known boards: {}; or give a path to a board .toml file)", known.join(", "))
    }

    /// Every value has a form the pin files can carry (the name becomes a
    /// folder name, so it cannot leave `constraints/`), and no pin serves two
    /// roles (functional, clock or debug).
    pub fn validate(&self) -> Result<()> {
        check_file_name("name", &self.name)?;
        for (key, v) in [("description", &self.description), ("family", &self.family), ("part", &self.part)] {
            check_text(key, v)?;
        }
        if let Some(p) = &self.package {
            check_text("package", p)?;
        }
        if let Some(s) = &self.iostandard {
            check_token("iostandard", s)?;
        }
        // What the library's writers can carry (its Lattice writer panics on
        // anything but LVCMOS33, its PCF writer on any I/O standard).
        match (self.format, self.iostandard.as_deref()) {
            (Format::Pcf, Some(s)) => bail!("iostandard: {s:?}: a PCF (iCE40) pin file carries no I/O standard; remove the key"),
            (Format::Lpf, Some(s)) if s != "LVCMOS33" => bail!("iostandard: {s:?}: the LPF writer knows LVCMOS33 only"),
            (Format::Xdc, None) => bail!("iostandard: missing; Vivado needs an I/O standard on every port (e.g. iostandard = \"LVCMOS33\")"),
            _ => {}
        }
        check_identifier("clock.port", &self.clock.port)?;
        check_token("clock.pin", &self.clock.pin)?;
        if !(1_000..=1_000_000_000).contains(&self.clock.hz) {
            bail!("clock.hz: {} Hz (must be 1 kHz ..= 1 GHz)", self.clock.hz);
        }
        let pinouts = std::iter::once(("pins", &self.pins))
            .chain(self.controller.as_ref().map(|c| ("controller.pins", &c.pins)))
            .chain(self.slcan.as_ref().map(|c| ("slcan.pins", &c.pins)));
        for (table, pins) in pinouts {
            for (role, pin) in pins {
                check_role(&format!("{table}.\"{role}\""), role)?;
                check_token(&format!("{table}.\"{role}\""), pin)?;
            }
        }
        for (i, pin) in self.debug.pins.iter().enumerate() {
            check_token(&format!("debug.pins[{i}]"), pin)?;
        }
        let mut used: BTreeMap<&str, String> = BTreeMap::new();
        claim_pin(&mut used, &self.clock.pin, format!("clock port {}", self.clock.port))?;
        for (role, pin) in &self.pins {
            claim_pin(&mut used, pin, format!("role {role}"))?;
        }
        for pin in &self.debug.pins {
            claim_pin(&mut used, pin, "a debug pin".into())?;
        }
        for (what, pins) in [("controller", &self.controller), ("slcan", &self.slcan)] {
            let Some(c) = pins else { continue };
            let mut used: BTreeMap<&str, String> = BTreeMap::new();
            claim_pin(&mut used, &self.clock.pin, format!("clock port {}", self.clock.port))?;
            for (role, pin) in &c.pins {
                claim_pin(&mut used, pin, format!("{what} role {role}"))?;
            }
        }
        Ok(())
    }

    /// The designs the board has a pinout for: `hub` (`[pins]`) and, with
    /// `[controller.pins]`, `controller`, with `[slcan.pins]`, `slcan`.
    pub fn designs(&self) -> Vec<&'static str> {
        let mut v = vec!["hub"];
        if self.controller.is_some() {
            v.push("controller");
        }
        if self.slcan.is_some() {
            v.push("slcan");
        }
        v
    }

    /// The role -> pin map and the free debug pins of one pinout.
    pub(crate) fn pinout(&self, which: Pinout) -> Result<(&BTreeMap<String, String>, Vec<&String>)> {
        match which {
            Pinout::Hub => Ok((&self.pins, self.debug.pins.iter().collect())),
            Pinout::Controller | Pinout::Slcan => {
                let (c, what) = match which {
                    Pinout::Controller => (self.controller.as_ref(), "controller"),
                    _ => (self.slcan.as_ref(), "slcan"),
                };
                let c = c.ok_or_else(|| anyhow!("{} has no {what} pinout ([{}])", self.label(), which.table()))?;
                let used: BTreeSet<&String> = c.pins.values().collect();
                Ok((&c.pins, self.debug.pins.iter().filter(|p| !used.contains(p)).collect()))
            }
        }
    }

    /// `board <name>`, after the file it came from if any (for messages).
    pub fn label(&self) -> String {
        match &self.source {
            Some(f) => format!("{f}: board {}", self.name),
            None => format!("board {}", self.name),
        }
    }

    /// The clock period in nanoseconds.
    pub fn clock_period_ns(&self) -> f64 {
        1e9 / self.clock.hz as f64
    }
}

/// A board name: it names the folder of the board's pin files.
fn check_file_name(key: &str, v: &str) -> Result<()> {
    let ok = !v.is_empty()
        && v.len() <= 64
        && !v.starts_with(['.', '-'])
        && v.chars().all(|c| c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-'));
    if !ok {
        bail!("{key}: {v:?} must be 1 to 64 letters, digits, '.', '_' or '-', not starting with '.' or '-' (it names the folder of the pin files)");
    }
    Ok(())
}

/// Free text written into a pin file's comment: one line, no quotes.
fn check_text(key: &str, v: &str) -> Result<()> {
    if v.chars().any(|c| c.is_control() || c == '"') || v.len() > 200 {
        bail!("{key}: {v:?} must be one line of at most 200 characters without quotes");
    }
    Ok(())
}

/// A pin name or an I/O standard: letters, digits and `_` (`H15`, `LVCMOS33`).
fn check_token(key: &str, v: &str) -> Result<()> {
    if v.is_empty() || v.len() > 32 || !v.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        bail!("{key}: {v:?} must be 1 to 32 letters, digits or _");
    }
    Ok(())
}

/// A top-level port name.
fn check_identifier(key: &str, v: &str) -> Result<()> {
    let ok = v.chars().next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && v.len() <= 64
        && v.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if !ok {
        bail!("{key}: {v:?} must be a port name (a letter or _, then letters, digits or _)");
    }
    Ok(())
}

/// A role's port name and, for `name[i]`, the index as written.
pub(crate) fn role_parts(v: &str) -> (&str, Option<&str>) {
    match v.strip_suffix(']').and_then(|s| s.split_once('[')) {
        Some((b, i)) => (b, Some(i)),
        None => (v, None),
    }
}

/// A role: `name` or `name[i]`.
fn check_role(key: &str, v: &str) -> Result<()> {
    let (base, idx) = role_parts(v);
    check_identifier(key, base).map_err(|_| anyhow!("{key}: role {v:?} must be a port name or name[index]"))?;
    if let Some(i) = idx {
        if i.is_empty() || i.len() > 6 || !i.chars().all(|c| c.is_ascii_digit()) {
            bail!("{key}: role {v:?} must be a port name or name[index]");
        }
    }
    Ok(())
}

fn claim_pin<'a>(used: &mut BTreeMap<&'a str, String>, pin: &'a str, role: String) -> Result<()> {
    if let Some(prev) = used.get(pin) {
        bail!("pin conflict: pin {pin} is assigned to {prev} and to {role}");
    }
    used.insert(pin, role);
    Ok(())
}

/// The pins a design needs.
#[derive(Debug, Clone, Default)]
pub struct DesignPins {
    /// Functional roles (every one must have a pin), e.g. `rst_n`, `rx[0]`.
    pub functional: Vec<String>,
    /// Debug output bits, in the order they should be placed.
    pub debug: Vec<String>,
}

impl DesignPins {
    /// Roles of a port: `name` for 1 bit, `name[0]`.. for vectors.
    pub fn port_roles(name: &str, bits: usize) -> Vec<String> {
        if bits == 1 {
            vec![name.to_string()]
        } else {
            (0..bits).map(|i| format!("{name}[{i}]")).collect()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_boards_parse() {
        for (n, _) in BUILTIN {
            let b = Board::lookup(n).unwrap();
            assert_eq!(&b.name, n);
        }
    }

    #[test]
    fn unknown_board_is_a_clear_error() {
        let e = Board::lookup("no-such-board").unwrap_err().to_string();
        assert!(e.contains("unknown board `no-such-board`") && e.contains("xsa-3s1000"), "{e}");
    }

    #[test]
    fn pin_conflict_is_rejected() {
        let text = BUILTIN[0].1.replace("\"rx[1]\" = \"H14\"", "\"rx[1]\" = \"H15\"");
        let e = Board::from_toml(&text).unwrap_err().to_string();
        assert!(e.contains("pin conflict: pin H15"), "{e}");
    }

    #[test]
    fn unknown_key_in_board_is_rejected() {
        let text = format!("{}\nbogus = 1\n", BUILTIN[0].1.split("[clock]").next().unwrap());
        assert!(Board::from_toml(&text).is_err());
    }

    fn builtin(name: &str) -> &'static str {
        BUILTIN.iter().find(|(n, _)| *n == name).unwrap().1
    }

    #[test]
    fn iostandard_must_suit_the_format() {
        let pcf = builtin("ice40-hx8k").replace("format = \"pcf\"", "format = \"pcf\"\niostandard = \"LVCMOS33\"");
        let e = Board::from_toml(&pcf).unwrap_err().to_string();
        assert!(e.contains("iostandard") && e.contains("PCF"), "{e}");
        let lpf = builtin("ulx3s").replace("iostandard = \"LVCMOS33\"", "iostandard = \"LVCMOS25\"");
        let e = Board::from_toml(&lpf).unwrap_err().to_string();
        assert!(e.contains("iostandard: \"LVCMOS25\"") && e.contains("LVCMOS33 only"), "{e}");
        let xdc = builtin("arty-a7").replace("iostandard = \"LVCMOS33\"", "");
        let e = Board::from_toml(&xdc).unwrap_err().to_string();
        assert!(e.contains("iostandard: missing"), "{e}");
    }

    #[test]
    fn every_builtin_board_has_both_pinouts() {
        for (n, _) in BUILTIN {
            let b = Board::lookup(n).unwrap();
            let want: &[&str] = if *n == "alchitry-cu" { &["hub", "controller", "slcan"] } else { &["hub", "controller"] };
            assert_eq!(b.designs(), want, "{n}");
        }
        let hub_only = builtin("ulx3s").split("[controller.pins]").next().unwrap().to_string();
        assert_eq!(Board::from_toml(&hub_only).unwrap().designs(), ["hub"]);
    }
}
