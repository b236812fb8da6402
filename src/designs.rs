//! The registry of generatable designs: every design `canstar generate` renders,
//! with its Verilog file, board top and pin files.
use crate::config::Config;
use crate::boards::pinfile::pin_file;
use crate::boards::{Board, DesignPins, Pinout, BUILTIN};
use crate::verilog::{block, board_top, header, vector_wrapper, Artifact, Root};
use rust_hdl::prelude::Block;
use anyhow::Result;
use std::io::Write as _;
use canstar_hdl::{btl, crc15, stuff, sync};

/// A top module's ports: (name, bits, is_output).
pub type Ports = Vec<(String, usize, bool)>;

/// The shared RTL blocks as standalone modules (`verilog-out/blocks/`).
pub fn blocks(config: &Config) -> Result<Vec<Artifact>> {
    Ok(vec![
        block(
            sync::Synchroniser::new(config.rtl.sync_depth),
            "canstar_synchroniser",
            &format!("input synchroniser, {} flip-flop(s), reset value recessive", config.rtl.sync_depth),
        ),
        block(sync::EdgeDetector::default(), "canstar_edge_detector", "edge detector"),
        block(crc15::Crc15::default(), "canstar_crc15", "CAN CRC-15, polynomial 0x4599"),
        block(stuff::BitStuffer::default(), "canstar_bit_stuffer", "CAN bit stuffer"),
        block(stuff::BitDestuffer::default(), "canstar_bit_destuffer", "CAN bit destuffer"),
        block(
            btl::BitTiming::default(),
            "canstar_bit_timing",
            "CAN bit timing logic (prescaler, segments, hard sync and resync, PH2 a field, IPT = min(PH2, 2) TQ)",
        ),
    ])
}

/// The CAN controller core (native interface) as `verilog-out/controller/canstar_can_core.v`.
pub fn controller(config: &Config) -> Result<Vec<Artifact>> {
    let mut a = block(
        canstar_controller::core::CanCore::with_sync_depth(config.rtl.sync_depth)
            .with_rec_rule(config.controller.rec_rule),
        "canstar_can_core",
        "CAN 2.0A/B protocol controller core, native interface (see controller/src/core.rs)",
    );
    a.path = std::path::PathBuf::from("controller/canstar_can_core.v");
    Ok(vec![a])
}

/// The SJA1000-compatible (PeliCAN) controller: register block on Wishbone,
/// RX FIFO, acceptance filters, around the CAN core, as
/// `verilog-out/controller/canstar_sja1000.v` (module `canstar_sja1000`, plus the board
/// top `canstar_sja1000_board` with an active-low reset), and its pin files on every
/// board with a controller pinout (or the one asked for).
pub fn sja1000(config: &Config, board: Option<&str>) -> Result<Vec<Artifact>> {
    let (verilog, board_name, ports) = sja1000_verilog(config);
    let boards = match board {
        Some(b) => vec![Board::lookup(b)?],
        None => hub_boards(None)?.into_iter().filter(|b| b.controller.is_some()).collect(),
    };
    let mut out = vec![verilog];
    out.extend(pin_files(&boards, Pinout::Controller, &board_name, &ports)?);
    Ok(out)
}

/// The pin files of a board top whose every port but `clock` is functional,
/// one per board, from the board's `pinout`.
fn pin_files(boards: &[Board], pinout: Pinout, board_name: &str, ports: &Ports) -> Result<Vec<Artifact>> {
    let mut pins = DesignPins::default();
    for (p, bits, _) in ports {
        if p != "clock" {
            pins.functional.extend(DesignPins::port_roles(p, *bits));
        }
    }
    boards
        .iter()
        .map(|b| {
            let f = pin_file(b, pinout, board_name, &pins)?;
            Ok(Artifact { root: Root::Constraints, path: format!("{}/{board_name}.{}", b.name, b.format.ext()).into(), contents: f.text })
        })
        .collect()
}

/// The SJA1000-compatible top's Verilog file (`controller/canstar_sja1000.v`), the
/// name of its board top (`canstar_sja1000_board`) and the board top's ports.
pub fn sja1000_verilog(config: &Config) -> (Artifact, String, Ports) {
    let (btr0, btr1) = crate::config::btr(&config.bit_timing);
    let mut uut = canstar_controller::sja1000::Sja1000::with_reset_timing(btr0, btr1)
        .with_rec_rule(config.controller.rec_rule);
    uut.connect_all();
    let name = "canstar_sja1000";
    let inner = canstar_hdl::flow::rename_top(&canstar_hdl::flow::emit(&uut), name);
    let board_name = format!("{name}_board");
    let (top, ports) = board_top(&inner, name, "rst", &board_name);
    let t = &config.bit_timing;
    let desc = format!(
        "SJA1000 (PeliCAN) compatible CAN controller, Wishbone B4 classic slave, 8-bit (see controller/src/sja1000/); \
         board top with active-low reset; BTR0/BTR1 after reset 0x{btr0:02X}/0x{btr1:02X} ({} clocks per TQ, {} TQ per bit, sample point {})",
        t.brp,
        t.ntq(),
        t.sp()
    );
    let verilog = Artifact {
        root: Root::Verilog,
        path: format!("controller/{name}.v").into(),
        contents: header(name, &desc) + &inner + "\n" + &top,
    };
    (verilog, board_name, ports)
}

/// The USB-to-CAN adapter speaking slcan (Lawicel ASCII) over a UART, around
/// the SJA1000 top, as `verilog-out/controller/canstar_slcan.v` (module
/// `canstar_slcan`, plus the board top `canstar_slcan_board` with an
/// active-low reset), and its pin files on every board with an `[slcan.pins]`
/// pinout (or the one asked for, when it has one).
pub fn slcan(config: &Config, board: Option<&str>) -> Result<Vec<Artifact>> {
    let (verilog, board_name, ports) = slcan_verilog(config)?;
    let boards: Vec<Board> = hub_boards(board)?.into_iter().filter(|b| b.slcan.is_some()).collect();
    let mut out = vec![verilog];
    out.extend(pin_files(&boards, Pinout::Slcan, &board_name, &ports)?);
    Ok(out)
}

/// The slcan adapter's Verilog file (`controller/canstar_slcan.v`), the name of
/// its board top (`canstar_slcan_board`) and the board top's ports.
pub fn slcan_verilog(config: &Config) -> Result<(Artifact, String, Ports)> {
    let p = config.slcan.params()?;
    let mut uut = canstar_controller::slcan::SlcanTop::new(&p).with_rec_rule(config.controller.rec_rule);
    uut.connect_all();
    let name = "canstar_slcan";
    let inner = canstar_hdl::flow::rename_top(&canstar_hdl::flow::emit(&uut), name);
    let board_name = format!("{name}_board");
    let (top, ports) = board_top(&inner, name, "rst", &board_name);
    let rates: Vec<String> = p
        .table
        .iter()
        .enumerate()
        .map(|(k, e)| match e {
            Some((b0, b1)) => format!("S{k} 0x{b0:02X}/0x{b1:02X}"),
            None => format!("S{k} -"),
        })
        .collect();
    let desc = format!(
        "USB-to-CAN adapter: slcan (Lawicel ASCII) over a UART, 8N1, {} baud ({} clocks per bit at {} Hz), around the SJA1000 top \
         (see controller/src/slcan/); ports clock, rst, uart_rx, uart_tx, rx, tx; board top with active-low reset; \
         Sn BTR0/BTR1: {}",
        config.slcan.baud,
        p.clocks_per_bit,
        p.clock_hz,
        rates.join(", ")
    );
    let verilog = Artifact {
        root: Root::Verilog,
        path: format!("controller/{name}.v").into(),
        contents: header(name, &desc) + &inner + "\n" + &top,
    };
    Ok((verilog, board_name, ports))
}

/// Boards a hub's pin files are generated for: the one asked for, or all built-in ones.
pub fn hub_boards(board: Option<&str>) -> Result<Vec<Board>> {
    match board {
        Some(b) => Ok(vec![Board::lookup(b)?]),
        None => BUILTIN.iter().map(|(n, _)| Board::lookup(n)).collect(),
    }
}

/// Functional port bits of a hub (everything else is a debug/status output).
pub fn is_functional(port: &str) -> bool {
    matches!(port, "rst_n" | "inject_fault" | "rx" | "reh_rx" | "tx" | "hub_tx")
}

/// The functional port bits of a hub's top with `ports` node ports and
/// `sublinks` interlinks (known before rendering, so that a board lacking a pin
/// fails at once; the rendered ports are checked again by [`pin_file`]).
pub fn hub_functional_roles(ports: usize, sublinks: usize) -> Vec<String> {
    let mut v = vec!["rst_n".to_string(), "inject_fault".to_string()];
    v.extend(DesignPins::port_roles("rx", ports));
    if sublinks > 0 {
        v.extend(DesignPins::port_roles("reh_rx", sublinks));
    }
    v.extend(DesignPins::port_roles("tx", ports));
    if sublinks > 0 {
        v.extend(DesignPins::port_roles("hub_tx", sublinks));
    }
    v
}

/// The reference ReCANcentrate hub (`[hub]` of the config, M interlinks) and a
/// CANcentrate hub (the same with M = 0), each as `verilog-out/hub/<name>.v`
/// (rust-hdl core plus a top with vector ports) and pin files per board.
pub fn hub(config: &Config, board: Option<&str>) -> Result<Vec<Artifact>> {
    let boards = hub_boards(board)?;
    let mut out = vec![];
    let rec = config.hub.clone();
    let cc = canstar_hub::config::HubConfig { sublinks: 0, ..config.hub.clone() };
    for (name, cfg) in [("canstar_hub", &rec), ("canstar_cancentrate", &cc)] {
        let need = DesignPins { functional: hub_functional_roles(cfg.ports, cfg.sublinks), debug: vec![] };
        for b in &boards {
            pin_file(b, Pinout::Hub, name, &need)?;
        }
    }
    for (name, cfg, what) in [
        ("canstar_hub", rec, "ReCANcentrate star hub"),
        ("canstar_cancentrate", cc, "CANcentrate star hub (no interlinks)"),
    ] {
        let (verilog, ports) = hub_verilog(&cfg, name, what)?;
        out.push(verilog);
        let mut pins = DesignPins::default();
        for (p, bits, _) in &ports {
            if p == "clock" {
                continue;
            }
            let roles = DesignPins::port_roles(p, *bits);
            if is_functional(p) {
                pins.functional.extend(roles);
            } else {
                pins.debug.extend(roles);
            }
        }
        for b in &boards {
            if b.clock.hz != cfg.clock_hz {
                // (a closed stderr is no reason to stop)
                let _ = writeln!(
                    std::io::stderr(),
                    "note: board {} clock is {} Hz, the hub is configured for {} Hz (bit timing counts clocks)",
                    b.name, b.clock.hz, cfg.clock_hz
                );
            }
            let f = pin_file(b, Pinout::Hub, name, &pins)?;
            out.push(Artifact { root: Root::Constraints, path: format!("{}/{name}.{}", b.name, b.format.ext()).into(), contents: f.text });
        }
    }
    Ok(out)
}

/// A hub's Verilog file (`hub/<name>.v`: its core and its top `name` with vector
/// ports, `what` in the header) and the top's ports; the configuration is checked first.
pub fn hub_verilog(cfg: &canstar_hub::config::HubConfig, name: &str, what: &str) -> Result<(Artifact, Ports)> {
    cfg.validate().map_err(|e| anyhow::anyhow!("hub: invalid [hub] configuration: {e}"))?;
    let (inner, wrapper, ports) = hub_top(cfg, name);
    let desc = format!(
        "{what}, N = {} ports, M = {} interlinks, {} Hz clock, coupling latency {} clocks",
        cfg.ports,
        cfg.sublinks,
        cfg.clock_hz,
        cfg.coupling_latency()
    );
    let verilog = Artifact { root: Root::Verilog, path: format!("hub/{name}.v").into(), contents: header(name, &desc) + &inner + "\n" + &wrapper };
    Ok((verilog, ports))
}

/// A hub's rust-hdl core (`<name>_core`), its top with vector ports and the top's ports.
fn hub_top(cfg: &canstar_hub::config::HubConfig, name: &str) -> (String, String, Vec<(String, usize, bool)>) {
    let mut h = canstar_hub::top::Hub::new(cfg);
    h.connect_all();
    let core = format!("{name}_core");
    let inner = canstar_hdl::flow::rename_top(&canstar_hdl::flow::emit(&h), &core);
    let (wrapper, ports) = vector_wrapper(&inner, &core, name);
    (inner, wrapper, ports)
}

/// The designs `canstar report` measures: (name, Verilog, top module).
pub fn report_designs(config: &Config) -> Result<Vec<(String, String, String)>> {
    let mut v = vec![];
    for a in blocks(config)?.into_iter().chain(controller(config)?).chain(sja1000(config, None)?).chain(slcan(config, None)?).chain(hub(config, None)?) {
        if a.root != Root::Verilog {
            continue;
        }
        let top = a.path.file_stem().unwrap().to_string_lossy().into_owned();
        v.push((top.clone(), a.contents, top));
    }
    Ok(v)
}


#[cfg(test)]
mod tests {
    use super::*;

    /// The port bits checked against a board before rendering are those the rendered top has.
    #[test]
    fn hub_functional_roles_match_the_rendered_top() {
        for (ports, sublinks) in [(1, 0), (2, 1), (3, 2)] {
            let cfg = canstar_hub::config::HubConfig { ports, sublinks, ..Default::default() };
            let (_, _, top) = hub_top(&cfg, "t");
            let mut rendered: Vec<String> =
                top.iter().filter(|(p, _, _)| is_functional(p)).flat_map(|(p, bits, _)| DesignPins::port_roles(p, *bits)).collect();
            let mut known = hub_functional_roles(ports, sublinks);
            rendered.sort();
            known.sort();
            assert_eq!(rendered, known, "N = {ports}, M = {sublinks}");
        }
    }
}
