//! `canstar bench`: the engines side by side ([`engines`]: rust-hdl, compiled models,
//! Verilator and the kernel on CanCore buses, the hub and the reference network), and
//! `canstar bench --btl`: throughput of the simulation kernel on bit-timing instances.

pub mod engines;
mod verilator;

use anyhow::Result;
use canstar_hdl::btl;
use canstar_sim::bench::{bench as run_bench, build_bus, BenchConfig};
use canstar_sim::HdlComponent;
use std::path::Path;

/// A bit-timing instance as a simulation component: 40 MHz clock, BRP 4,
/// T10/6/4 (1 Mbit/s), held in reset for its first two cycles. Its RX is the
/// bus; the benchmark's pattern driver puts pseudo-random bits on the bus.
fn btl_node(i: usize, clock: canstar_sim::ClockSpec) -> HdlComponent<btl::BitTiming> {
    let cfg = btl::BtlConfig::from_fields(4, 1, 4, 4, 4, false);
    let mut b = btl::BitTiming::default();
    b.set_config(&cfg);
    let mut n = 0u32;
    HdlComponent::new(
        &format!("btl{i}"),
        clock,
        b,
        1,
        0,
        move |b, v| {
            b.reset.next = n < 2;
            n = n.saturating_add(1);
            b.rx.next = v[0];
        },
        |_, _| {},
    )
}

/// `canstar bench`: simulated clock cycles per second of bit-timing
/// instances, alone and sharing a bus (nodes spread over +-100 ppm).
pub fn bench(cycles: u64, nodes: &[usize], out: &mut dyn std::io::Write) -> Result<()> {
    anyhow::ensure!(cycles > 0, "--cycles must be positive");
    anyhow::ensure!(nodes.iter().all(|&n| n >= 1), "node counts must be at least 1");
    writeln!(out, "canstar bench: bit timing logic (canstar_hdl::btl::BitTiming), 40 MHz clocks, 1 Mbit/s, direct-drive kernel")?;
    let mut first = true;
    for &n in nodes {
        let cfg = BenchConfig {
            single_cycles: if first { cycles } else { 1 },
            bus_nodes: n,
            bus_cycles_per_node: (cycles / n as u64).max(1),
            ..BenchConfig::default()
        };
        let r = run_bench(&cfg, btl_node);
        if first {
            writeln!(
                out,
                "1 instance alone:    {:>12.0} cycles/s ({} cycles in {:.2} s)",
                r.single_cycles_per_sec, r.single_cycles, r.single_secs
            )?;
            first = false;
        }
        writeln!(
            out,
            "{n:>2} instances on a bus: {:>12.0} cycles/s in total, {:>12.0} cycles/s per instance ({} cycles in {:.2} s)",
            r.bus_cycles_per_sec, r.bus_node_cycles_per_sec, r.bus_cycles, r.bus_secs
        )?;
    }
    Ok(())
}

/// Simulate `nodes` bit-timing instances on a bus for `cycles` clock cycles
/// per node and write a VCD of every instance's signals and every bus wire
/// (or only the signals matching `signals`, see `canstar_sim::vcd`).
pub fn bench_vcd(path: &Path, nodes: usize, cycles: u64, signals: Option<&[String]>, seed: u64) -> Result<()> {
    anyhow::ensure!(nodes >= 1, "node count must be at least 1");
    let cfg = BenchConfig { seed, ..BenchConfig::default() };
    let mut sim = build_bus(&cfg, nodes, &mut btl_node);
    let filter: Option<Vec<&str>> = signals.map(|v| v.iter().map(|s| s.as_str()).collect());
    sim.start_vcd_file(path, filter.as_deref())?;
    sim.run_until(cfg.period_ps * cycles);
    sim.finish_vcd()?;
    Ok(())
}
