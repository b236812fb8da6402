//! The roles `canstar build` makes bitstreams for: each is a design's Verilog,
//! the name of its board top, which of the board's pinouts it uses, which of
//! its ports are functional (the rest are debug outputs) and its nominal
//! design clock. Adding a role is adding one entry to [`ROLES`].

use crate::boards::Pinout;
use crate::config::Config;
use anyhow::{anyhow, Result};

/// The controller's nominal design clock: 16 MHz (1 Mbit/s with the power-up
/// bit timing of 2 clocks per TQ and 8 TQ per bit; the host rewrites BTR0/BTR1).
pub const CONTROLLER_CLOCK_HZ: u64 = 16_000_000;

/// A design rendered for a bitstream.
#[derive(Debug, Clone)]
pub struct Design {
    /// The Verilog file (every module the board top needs).
    pub verilog: String,
    /// The board top: ports `clock` (design clock) and `rst_n` (active-low reset) among others.
    pub top: String,
    /// The board top's ports: (name, bits, is_output).
    pub ports: Vec<(String, usize, bool)>,
    /// The functional ports (every bit needs a pin); the other outputs are debug outputs.
    pub functional: Vec<String>,
    /// The nominal design clock, Hz.
    pub clock_hz: u64,
}

/// One buildable role.
pub struct Role {
    /// The name on the command line (`hub`).
    pub name: &'static str,
    /// What it is, for `canstar build --help` and messages.
    pub what: &'static str,
    /// The board pinout it uses.
    pub pinout: Pinout,
    /// Render the design from a configuration.
    pub render: fn(&Config) -> Result<Design>,
}

fn hub(config: &Config) -> Result<Design> {
    let name = "canstar_hub";
    let (verilog, ports) = crate::designs::hub_verilog(&config.hub, name, "ReCANcentrate star hub")?;
    let functional = ports.iter().filter(|(p, _, _)| crate::designs::is_functional(p)).map(|(p, _, _)| p.clone()).collect();
    Ok(Design { verilog: verilog.contents, top: name.into(), ports, functional, clock_hz: config.hub.clock_hz })
}

fn controller(config: &Config) -> Result<Design> {
    let (verilog, top, ports) = crate::designs::sja1000_verilog(config);
    let functional = ports.iter().filter(|(p, _, _)| p != "clock").map(|(p, _, _)| p.clone()).collect();
    Ok(Design { verilog: verilog.contents, top, ports, functional, clock_hz: CONTROLLER_CLOCK_HZ })
}

fn slcan(config: &Config) -> Result<Design> {
    let (verilog, top, ports) = crate::designs::slcan_verilog(config)?;
    let functional = ports.iter().filter(|(p, _, _)| p != "clock").map(|(p, _, _)| p.clone()).collect();
    Ok(Design { verilog: verilog.contents, top, ports, functional, clock_hz: config.slcan.clock_hz })
}

/// Every role, in the order `canstar build --help` lists them.
pub const ROLES: &[Role] = &[
    Role { name: "hub", what: "the ReCANcentrate star hub (canstar_hub, [hub] of the configuration)", pinout: Pinout::Hub, render: hub },
    Role {
        name: "controller",
        what: "the SJA1000-compatible controller with its Wishbone slave on pins (canstar_sja1000_board)",
        pinout: Pinout::Controller,
        render: controller,
    },
    Role {
        name: "slcan",
        what: "the USB-to-CAN adapter: slcan over the board's USB UART around the SJA1000 top (canstar_slcan_board, [slcan] of the configuration)",
        pinout: Pinout::Slcan,
        render: slcan,
    },
];

/// A role by name.
pub fn lookup(name: &str) -> Result<&'static Role> {
    ROLES.iter().find(|r| r.name == name).ok_or_else(|| {
        let known: Vec<&str> = ROLES.iter().map(|r| r.name).collect();
        anyhow!("unknown role `{name}` (known roles: {})", known.join(", "))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roles_render_with_a_clock_a_reset_and_their_nominal_clock() {
        let cfg = Config::default();
        for r in ROLES {
            let d = (r.render)(&cfg).unwrap();
            assert!(d.verilog.contains(&format!("module {}(", d.top)), "{}", r.name);
            for need in ["clock", "rst_n"] {
                assert!(d.ports.iter().any(|(p, b, o)| p == need && *b == 1 && !o), "{}: {need}", r.name);
            }
            assert!(d.functional.iter().all(|f| d.ports.iter().any(|(p, _, _)| p == f)), "{}", r.name);
        }
        assert_eq!((lookup("hub").unwrap().render)(&cfg).unwrap().clock_hz, 14_740_000);
        assert_eq!((lookup("controller").unwrap().render)(&cfg).unwrap().clock_hz, 16_000_000);
        assert_eq!((lookup("slcan").unwrap().render)(&cfg).unwrap().clock_hz, cfg.slcan.clock_hz);
        let e = lookup("router").err().unwrap().to_string();
        assert_eq!(e, "unknown role `router` (known roles: hub, controller, slcan)");
    }
}
