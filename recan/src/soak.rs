//! Fault-free soak of the reference two-hub network (hub.md A1): full load, every
//! oscillator at the tolerance limit of the bit timing, optionally with the legal events
//! of healthy nodes ([`crate::events`]); counts frames, blames, isolations, errors and the
//! worst TEC/REC (`canstar soak`).
//!
//! A soak of F frames is a list of independent *chunks* (runs of `chunk_frames` frames,
//! each with its own seed: clock phases, oscillator signs, traffic phase and event
//! instants), so it runs on several threads and on several machines (`--shard`) and every
//! chunk can be rerun alone from its seed.

use crate::campaign::Shard;
use crate::events::{self, NodeEvent};
use crate::{RunResult, RunSpec};
use crate::spec::NetworkSpec;
use canstar_hdl::timing::BtlConfig;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

/// Oscillator tolerance of a bit timing (ISO 11898-1): df <= min(min(PH1, PH2) /
/// (2 (13 NBT - PH2)), SJW / (20 NBT)), in ppm.
pub fn tolerance_ppm(t: &BtlConfig) -> f64 {
    let (ph1, ph2, sjw, nbt) = (t.ph1 as f64, t.ph2 as f64, t.sjw as f64, t.ntq() as f64);
    let a = ph1.min(ph2) / (2.0 * (13.0 * nbt - ph2));
    let b = sjw / (20.0 * nbt);
    a.min(b) * 1e6
}

/// What a soak runs.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SoakSettings {
    /// Frames in total (delivered frames, summed over the chunks).
    pub frames: u64,
    /// Frames per chunk.
    pub chunk_frames: u32,
    /// Master seed.
    pub seed: u64,
    /// Oscillator offset magnitude in ppm; every hub and controller gets +ppm or -ppm
    /// (None: the tolerance limit of the bit timing, [`tolerance_ppm`]).
    pub ppm: Option<f64>,
    /// Add the legal events of healthy nodes (error-passive controllers, overload
    /// frames, late joiners, nodes switched off and on), see [`crate::events`].
    pub events: bool,
    /// Node controllers at 14.74 MHz (TQ 2 clocks, same bit timing) instead of the
    /// reference 29.48 MHz: half the simulation cost.
    pub fast: bool,
    /// The network to soak (None: the reference network, [`NetworkSpec::default`]);
    /// its oscillator offsets, first transmitters and start time are replaced per chunk.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub network: Option<NetworkSpec>,
}

impl Default for SoakSettings {
    fn default() -> Self {
        SoakSettings { frames: 1_000_000, chunk_frames: 2000, seed: 1, ppm: None, events: false, fast: false, network: None }
    }
}

impl SoakSettings {
    /// Number of chunks.
    pub fn chunks(&self) -> u64 {
        self.frames.div_ceil(self.chunk_frames.max(1) as u64)
    }
    /// Seed of chunk `i`.
    pub fn chunk_seed(&self, i: u64) -> u64 {
        crate::campaign::run_seed(self.seed, if self.events { "soak-events" } else { "soak" }, i as u32)
    }
    /// The network soaked, before each chunk's oscillators, first transmitters and
    /// start time are set.
    pub fn network_spec(&self) -> NetworkSpec {
        match (&self.network, self.fast) {
            (Some(n), _) => n.clone(),
            (None, true) => NetworkSpec::fast(),
            (None, false) => NetworkSpec::default(),
        }
    }
    /// The chunk indices of `shard` (all without one).
    pub fn plan(&self, shard: Option<Shard>) -> Vec<u64> {
        (0..self.chunks()).filter(|&i| shard.is_none_or(|s| s.contains(i as usize))).collect()
    }
}

/// The outcome of one chunk.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct ChunkOutcome {
    pub index: u64,
    pub seed: u64,
    /// Frames delivered.
    pub frames: u64,
    /// Charged blames: a judge unit blamed its port or sublink and charged it (`bic += 8`,
    /// lifetime count), both hubs, one per unit and blame.
    pub blames: u64,
    /// Blames that started the hub's error flag without charging anyone (another unit's
    /// glitch, or a dominant stuff bit: judge.rs §5.8 and the stuff-bit rule).
    #[serde(default)]
    pub uncharged: u64,
    /// Replica-rule charges of sublinks (hub.md §5.7), both hubs.
    #[serde(default)]
    pub replica_charges: u64,
    /// Ports and sublinks isolated ("hub h port i", "hub h sublink j").
    pub isolations: Vec<String>,
    /// Error events of controllers.
    pub errors: u64,
    /// Highest TEC and REC of any controller (error-passive controllers loaded by an
    /// event excluded).
    pub worst_tec: u32,
    pub worst_rec: u32,
    /// Frames the Receiver missed, quarantines, failed run checks.
    pub problems: Vec<String>,
    /// Shortest run of equal level seen on any node port input / sublink input of a
    /// hub, in hub clocks (None: none shorter than 32).
    pub min_port_pulse: Option<u32>,
    pub min_sublink_pulse: Option<u32>,
    /// Edges on the port inputs / sublink inputs of both hubs by phase (see
    /// [`crate::rtl_hub::HubStats::edge_phase`]).
    pub port_edge_phase: Vec<u64>,
    pub sublink_edge_phase: Vec<u64>,
    /// The events applied (descriptions).
    pub events: Vec<String>,
    /// Where the first blames of the chunk fell (at most 8): "hub 1 sublink 0: CrcDelim
    /// bit 0 at bit time 24104", the field as the hub's frame monitor saw it.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub blame_sites: Vec<String>,
    pub sim_cycles: u64,
}

impl ChunkOutcome {
    /// Zero blames, zero isolations and no problem.
    pub fn clean(&self) -> bool {
        self.blames == 0 && self.replica_charges == 0 && self.isolations.is_empty() && self.problems.is_empty()
    }
}

/// The network and run of chunk `index`.
pub fn chunk_spec(s: &SoakSettings, index: u64) -> (RunSpec, Vec<NodeEvent>) {
    let seed = s.chunk_seed(index);
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x50a4);
    let mut net = s.network_spec();
    let ppm = s.ppm.unwrap_or_else(|| {
        net.nodes.iter().flat_map(|n| [&n.a.timing, &n.b.timing]).map(tolerance_ppm).fold(tolerance_ppm(&net.hub.timing), f64::min)
    });
    let mut sign = || if rng.gen_bool(0.5) { ppm } else { -ppm };
    for h in &mut net.hubs {
        h.ppm = sign();
    }
    for nd in &mut net.nodes {
        for c in 0..2 {
            nd.ctrl_mut(c).ppm = sign();
        }
    }
    for nd in &mut net.nodes {
        nd.initial_tx = rng.gen_range(0..2);
    }
    net.driver.start_bits = rng.gen_range(15..60);
    let evs = if s.events { events::random_events(&mut rng, &net, s.chunk_frames) } else { vec![] };
    if evs.iter().any(|e| matches!(e, NodeEvent::ErrorPassive { .. })) {
        // an error-passive controller has TEC >= 128: the warning-limit quarantine of the
        // node model would take it out at once
        net.driver.warning_limit = 255;
    }
    let mut spec = RunSpec::new(net, seed, s.chunk_frames);
    spec.events = evs.clone();
    (spec, evs)
}

/// Shortest run of equal level on the port inputs (`ports`) or the sublink inputs of
/// either hub (inputs `0..np` are ports).
fn min_pulse(r: &RunResult, np: usize, ports: bool) -> Option<u32> {
    let mut best: Option<u32> = None;
    for hub in &r.short_runs {
        let range = if ports { 0..np } else { np..hub.len() };
        for k in range {
            if let Some(len) = hub[k].iter().position(|&c| c > 0) {
                best = Some(best.map_or(len as u32, |b| b.min(len as u32)));
            }
        }
    }
    best
}

fn edge_phases(r: &RunResult, np: usize, ports: bool) -> Vec<u64> {
    let mut v = vec![0u64; 64];
    for hub in &r.edge_phase {
        let range = if ports { 0..np } else { np..hub.len() };
        for k in range {
            for (i, c) in hub[k].iter().enumerate() {
                v[i] += c;
            }
        }
    }
    v
}

/// Run chunk `index`.
pub fn run_chunk(s: &SoakSettings, index: u64) -> ChunkOutcome {
    run_chunk_vcd(s, index, None)
}

/// Run chunk `index`, writing a VCD (if `vcd` is given: path, first bit time, number of
/// bit times; a failure to write it is a problem of the outcome, as every run failure).
pub fn run_chunk_vcd(s: &SoakSettings, index: u64, vcd: Option<(&std::path::Path, u64, u64)>) -> ChunkOutcome {
    let (mut spec, evs) = chunk_spec(s, index);
    if let Some((p, from, bits)) = vcd {
        let bit = spec.network.bit_time_ps();
        spec.vcd = Some(p.to_path_buf());
        spec.vcd_window_ps = Some((from.saturating_mul(bit), from.saturating_add(bits).saturating_mul(bit)));
    }
    let r = crate::run(&spec);
    let passive: Vec<(usize, usize)> = evs
        .iter()
        .filter_map(|e| match *e {
            NodeEvent::ErrorPassive { node, ctrl, .. } => Some((node, ctrl)),
            _ => None,
        })
        .collect();
    let (mut tec, mut rec) = (0, 0);
    for c in &r.counters {
        if !passive.contains(&(c.node, c.ctrl)) {
            tec = tec.max(c.tec);
            rec = rec.max(c.rec);
        }
    }
    let mut problems: Vec<String> = r.failures.clone();
    for &(k, c, t) in &r.quarantined {
        problems.push(format!("node {k} controller {} quarantined at bit {}", "AB".as_bytes()[c] as char, t / r.bit_time_ps.max(1)));
    }
    ChunkOutcome {
        index,
        seed: spec.seed,
        frames: r.delivered,
        blames: r.blames.iter().filter(|b| b.5).count() as u64,
        uncharged: r.blames.iter().filter(|b| !b.5).count() as u64,
        replica_charges: r.replica_charges,
        isolations: r
            .isolated
            .iter()
            .map(|i| format!("{} ({})", i.what, i.cause))
            .collect(),
        errors: r.ctrl_errors.len() as u64,
        worst_tec: tec,
        worst_rec: rec,
        problems,
        min_port_pulse: min_pulse(&r, spec.network.hub.ports, true),
        min_sublink_pulse: min_pulse(&r, spec.network.hub.ports, false),
        events: r.events_applied.clone(),
        port_edge_phase: edge_phases(&r, spec.network.hub.ports, true),
        sublink_edge_phase: edge_phases(&r, spec.network.hub.ports, false),
        blame_sites: blame_sites(&r, spec.network.hub.ports),
        sim_cycles: r.sim_cycles,
    }
}

/// A blame site of a blame that was not charged (marked by [`blame_sites`]).
fn uncharged_site(site: &str) -> bool {
    site.ends_with(" (not charged)")
}

/// The first blames of a run, described ([`ChunkOutcome::blame_sites`]).
fn blame_sites(r: &RunResult, ports: usize) -> Vec<String> {
    r.blames
        .iter()
        .take(8)
        .map(|&(hub, t, unit, field, pos, charged)| {
            let who = if unit < ports { format!("port {unit}") } else { format!("sublink {}", unit - ports) };
            let f = canstar_hub::frame_state::Field::from_code(field as u64);
            let note = if charged { "" } else { " (not charged)" };
            format!("hub {hub} {who}: {f:?} bit {pos} at bit time {}{note}", t / r.bit_time_ps.max(1))
        })
        .collect()
}

/// Run the chunks `plan` on `jobs` threads; `progress` is called in the calling thread
/// after each chunk (completion order). The result is in plan order.
pub fn execute(s: &SoakSettings, plan: &[u64], jobs: usize, mut progress: impl FnMut(&ChunkOutcome)) -> Vec<ChunkOutcome> {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(jobs.max(1)).build().expect("rayon pool");
    let (tx, rx) = std::sync::mpsc::channel::<ChunkOutcome>();
    let mut out = vec![];
    pool.in_place_scope(|sc| {
        for &i in plan {
            let tx = tx.clone();
            sc.spawn(move |_| {
                let _ = tx.send(run_chunk(s, i));
            });
        }
        drop(tx);
        for c in rx.iter() {
            progress(&c);
            out.push(c);
        }
    });
    out.sort_by_key(|c| c.index);
    out
}

/// Aggregate of a soak (or one shard of it).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SoakReport {
    pub settings: Option<SoakSettings>,
    pub chunks: Vec<ChunkOutcome>,
}

impl SoakReport {
    pub fn frames(&self) -> u64 {
        self.chunks.iter().map(|c| c.frames).sum()
    }
    pub fn blames(&self) -> u64 {
        self.chunks.iter().map(|c| c.blames).sum()
    }
    pub fn uncharged(&self) -> u64 {
        self.chunks.iter().map(|c| c.uncharged).sum()
    }
    pub fn replica_charges(&self) -> u64 {
        self.chunks.iter().map(|c| c.replica_charges).sum()
    }
    pub fn isolations(&self) -> usize {
        self.chunks.iter().map(|c| c.isolations.len()).sum()
    }
    pub fn ok(&self) -> bool {
        self.chunks.iter().all(|c| c.clean())
    }
    /// The summary lines printed by `canstar soak`.
    pub fn summary(&self) -> String {
        let worst_tec = self.chunks.iter().map(|c| c.worst_tec).max().unwrap_or(0);
        let worst_rec = self.chunks.iter().map(|c| c.worst_rec).max().unwrap_or(0);
        let errors: u64 = self.chunks.iter().map(|c| c.errors).sum();
        let events: usize = self.chunks.iter().map(|c| c.events.len()).sum();
        let minp = self.chunks.iter().filter_map(|c| c.min_port_pulse).min();
        let mins = self.chunks.iter().filter_map(|c| c.min_sublink_pulse).min();
        let mut s = format!(
            "frames {}  chunks {}  blames {}  isolations {}  worst TEC {worst_tec} REC {worst_rec}  controller errors {errors}  events {events}  uncharged blames {}  replica charges {}\n",
            self.frames(),
            self.chunks.len(),
            self.blames(),
            self.isolations(),
            self.uncharged(),
            self.replica_charges()
        );
        s += &format!(
            "shortest pulse on a port input: {}, on a sublink input: {} (hub clocks)\n",
            minp.map_or("none below 32".into(), |v| v.to_string()),
            mins.map_or("none below 32".into(), |v| v.to_string())
        );
        if let Some(st) = &self.settings {
            let net = st.network_spec();
            s += &(net.propagation_budget().describe(&net) + "\n");
        }
        for (name, get) in [("port", 0usize), ("sublink", 1)] {
            let mut h = vec![0u64; 64];
            for c in &self.chunks {
                let src = if get == 0 { &c.port_edge_phase } else { &c.sublink_edge_phase };
                for (i, x) in src.iter().enumerate() {
                    h[i] += x;
                }
            }
            let fmt = |r: &[u64]| r.iter().enumerate().filter(|(_, &x)| x > 0).map(|(i, x)| format!("{i}:{x}")).collect::<Vec<_>>().join(" ");
            s += &format!("{name} edge phases (clocks after the monitor's sample strobe): falling {}; rising {}\n", fmt(&h[..32]), fmt(&h[32..]));
        }
        let unclean = self.chunks.iter().filter(|c| !c.clean()).count();
        if unclean > 0 {
            // where the charged blames of the unclean chunks fell, by the monitor's field
            // and bit (first 8 per chunk; uncharged ones are listed with the clean chunks)
            let mut sites = std::collections::BTreeMap::<String, usize>::new();
            for site in self.chunks.iter().filter(|c| !c.clean()).flat_map(|c| &c.blame_sites).filter(|b| !uncharged_site(b)) {
                let place = site.split(": ").nth(1).and_then(|x| x.split(" at ").next()).unwrap_or(site);
                *sites.entry(place.to_string()).or_default() += 1;
            }
            let list = sites.iter().map(|(k, v)| format!("{k} ({v})")).collect::<Vec<_>>().join(", ");
            s += &format!("chunks not clean: {unclean} of {}; blames in: {list}\n", self.chunks.len());
        }
        let with_uncharged: Vec<String> = self
            .chunks
            .iter()
            .filter(|c| c.clean() && c.uncharged > 0)
            .map(|c| format!("{} ({})", c.index, c.blame_sites.first().map_or("", |b| b.as_str())))
            .collect();
        if !with_uncharged.is_empty() {
            s += &format!(
                "clean chunks with uncharged blames (the hub started its error flag, nobody was charged): {}\n",
                with_uncharged.join(", ")
            );
        }
        for c in self.chunks.iter().filter(|c| !c.clean()) {
            s += &format!(
                "chunk {} seed {}: blames {} isolations [{}]{} {}{}\n",
                c.index,
                c.seed,
                c.blames,
                c.isolations.join(", "),
                if c.replica_charges > 0 { format!(" replica charges {}", c.replica_charges) } else { String::new() },
                c.problems.join("; "),
                c.blame_sites.iter().find(|b| !uncharged_site(b)).map_or(String::new(), |b| format!(" first blame: {b}"))
            );
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn summary_counts_unclean_chunks_and_where_the_blames_fell() {
        let clean = ChunkOutcome {
            index: 0,
            frames: 100,
            ..Default::default()
        };
        let bad = ChunkOutcome {
            index: 1,
            seed: 7,
            frames: 100,
            blames: 3,
            blame_sites: vec![
                "hub 0 port 2: Data bit 3 at bit time 5 (not charged)".into(),
                "hub 1 sublink 0: CrcDelim bit 0 at bit time 10".into(),
                "hub 1 port 2: CrcDelim bit 0 at bit time 900".into(),
                "hub 0 sublink 1: AckDelim bit 0 at bit time 11".into(),
            ],
            ..Default::default()
        };
        // a clean chunk's uncharged blame is not listed with the unclean chunks' sites
        let clean_uncharged = ChunkOutcome {
            index: 2,
            frames: 100,
            uncharged: 1,
            blame_sites: vec!["hub 0 port 1: Eof bit 2 at bit time 7 (not charged)".into()],
            ..Default::default()
        };
        let r = SoakReport {
            settings: None,
            chunks: vec![clean, bad, clean_uncharged],
        };
        let s = r.summary();
        assert!(
            s.starts_with("frames 300  chunks 3  blames 3  isolations 0"),
            "{s}"
        );
        assert!(
            s.contains(
                "chunks not clean: 1 of 3; blames in: AckDelim bit 0 (1), CrcDelim bit 0 (2)"
            ),
            "{s}"
        );
        assert!(s.contains("chunk 1 seed 7: blames 3 isolations []  first blame: hub 1 sublink 0: CrcDelim bit 0 at bit time 10"), "{s}");
        assert!(!r.ok());
    }

    #[test]
    fn uncharged_blames_are_reported_but_leave_a_chunk_clean() {
        let c = ChunkOutcome {
            index: 4,
            frames: 100,
            uncharged: 2,
            blame_sites: vec!["hub 0 port 1: Data bit 1 at bit time 45095 (not charged)".into()],
            ..Default::default()
        };
        assert!(c.clean());
        let r = SoakReport { settings: None, chunks: vec![c] };
        let s = r.summary();
        assert!(s.starts_with("frames 100  chunks 1  blames 0  isolations 0"), "{s}");
        assert!(s.lines().next().unwrap().ends_with("uncharged blames 2  replica charges 0"), "{s}");
        assert!(
            s.contains("clean chunks with uncharged blames (the hub started its error flag, nobody was charged): 4 (hub 0 port 1: Data bit 1 at bit time 45095 (not charged))"),
            "{s}"
        );
        assert!(!s.contains("chunks not clean"), "{s}");
        assert!(r.ok());
    }

    #[test]
    fn replica_charges_make_a_chunk_unclean() {
        let c = ChunkOutcome { index: 5, seed: 9, frames: 100, replica_charges: 1, ..Default::default() };
        assert!(!c.clean());
        let r = SoakReport { settings: None, chunks: vec![c] };
        let s = r.summary();
        assert!(s.lines().next().unwrap().ends_with("replica charges 1"), "{s}");
        assert!(s.contains("chunk 5 seed 9: blames 0 isolations [] replica charges 1"), "{s}");
        assert!(!r.ok());
    }

    #[test]
    fn the_tolerance_is_the_smallest_of_every_timing_in_the_network() {
        let mut net = NetworkSpec::default();
        let reference = tolerance_ppm(&net.hub.timing);
        net.nodes[2].b.timing.sjw = 2; // a larger SJW raises this controller's tolerance
        net.nodes[1].b.timing.prop = 5; // a longer bit with the same SJW lowers it (10 TQ: 5000 ppm)
        let s = SoakSettings {
            network: Some(net.clone()),
            frames: 10,
            chunk_frames: 10,
            ..Default::default()
        };
        let (spec, _) = chunk_spec(&s, 0);
        let want = net
            .nodes
            .iter()
            .flat_map(|n| [&n.a.timing, &n.b.timing])
            .map(tolerance_ppm)
            .fold(reference, f64::min);
        assert!(
            (want - 5000.0).abs() < 1e-6,
            "node 1 B sets the tolerance: {want}"
        );
        assert!(spec.network.hubs.iter().all(|h| h.ppm.abs() == want));
        assert!(spec
            .network
            .nodes
            .iter()
            .all(|n| n.a.ppm.abs() == want && n.b.ppm.abs() == want));
    }
}
