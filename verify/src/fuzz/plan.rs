//! The random plan of one fuzz run: node timings, clocks, delays, traffic and disturbances.

use super::*;

/// Nominal bit-timing choices (PROP, PH1, SJW), 100 ns per TQ.
const TIMINGS: [(u32, u32, u32); 4] = [(1, 4, 4), (1, 4, 2), (5, 2, 1), (8, 8, 1)];

#[derive(Clone, Debug)]
pub(super) enum Action {
    Request { node: usize, frame: Frame },
    /// Interference (a [`FaultMode`]) on the node's receive path during [t, t + len).
    Disturb { node: usize, mode: FaultMode, len: u64 },
    /// `count` inverted windows of `len`, one every `every`.
    Flip { node: usize, len: u64, every: u64, count: usize },
}

pub(super) struct Plan {
    pub(super) cfgs: Vec<(NodeConfig, ClockSpec)>,
    pub(super) delays: Vec<NodeDelays>,
    pub(super) bit_ps: u64,
    pub(super) actions: Vec<(u64, Action)>,
    /// Disturbance windows per node: (start, end) ps.
    pub(super) windows: Vec<Vec<(u64, u64)>>,
    pub(super) quiet_from: u64,
}

/// A frame for `node`. A (IDE, id, RTR) key keeps its content for ever and may be shared by at
/// most two nodes, and only with 3 or more nodes (so that identical frames sent at once always
/// leave a receiver to acknowledge them).
fn random_frame(rng: &mut ChaCha8Rng, owned: &mut HashMap<(bool, u32, bool), (Frame, Vec<usize>)>, node: usize, n: usize) -> Frame {
    loop {
        let f = random_frame_once(rng, owned);
        let key = (f.ide, f.id, f.rtr);
        let users = &mut owned.get_mut(&key).unwrap().1;
        if users.contains(&node) {
            return f;
        }
        if users.is_empty() || (n >= 3 && users.len() < 2) {
            users.push(node);
            return f;
        }
    }
}

fn random_frame_once(rng: &mut ChaCha8Rng, owned: &mut HashMap<(bool, u32, bool), (Frame, Vec<usize>)>) -> Frame {
    let ide = rng.gen_bool(0.4);
    // small id spaces so that equal ids, equal base ids and data/remote pairs happen
    let id = if ide {
        let base = rng.gen_range(0..16u32) << 7 | rng.gen_range(0..2u32);
        (base << 18) | if rng.gen_bool(0.5) { rng.gen_range(0..4) } else { rng.gen_range(0..1 << 18) }
    } else {
        rng.gen_range(0..16u32) << 7 | rng.gen_range(0..2u32)
    };
    let rtr = rng.gen_bool(0.15);
    let key = (ide, id, rtr);
    if let Some((f, _)) = owned.get(&key) {
        return f.clone();
    }
    let dlc = rng.gen_range(0..16u8);
    let f = if rtr {
        Frame::remote(ide, id, dlc)
    } else {
        let mode = rng.gen_range(0..4);
        let data: Vec<u8> = (0..8)
            .map(|_| match mode {
                0 => 0x00,
                1 => 0xff,
                _ => rng.gen(),
            })
            .collect();
        Frame::data(ide, id, dlc, &data)
    };
    owned.insert(key, (f.clone(), Vec::new()));
    f
}

pub(super) fn plan(seed: u64, opts: &RunOptions) -> Plan {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let n = rng.gen_range(2..=5usize);
    let (prop, ph1, sjw) = TIMINGS[rng.gen_range(0..TIMINGS.len())];
    let ph2 = ph1.max(2);
    let ntq = 1 + prop + ph1 + ph2;
    let df = (sjw as f64 / (20.0 * ntq as f64)).min(ph1.min(ph2) as f64 / (2.0 * (13.0 * ntq as f64 - ph2 as f64)));
    let max_ppm = df * 1e6 * 0.4;
    let bit_ps = ntq as u64 * 100_000;
    let mut cfgs = Vec::new();
    let mut delays = Vec::new();
    for i in 0..n {
        let brp = if rng.gen_bool(0.25) { 2 } else { 1 };
        let period = 100_000 / brp as u64;
        let ppm = rng.gen_range(-max_ppm..=max_ppm);
        let clock = ClockSpec::new(period).with_ppm(ppm).with_phase(rng.gen_range(0..period));
        let cfg = NodeConfig::named(&format!("n{}", i + 1)).timing(brp, prop, ph1, sjw).engine(opts.engine);
        cfgs.push((cfg, clock));
        let d = rng.gen_range(0..=20_000 * prop as u64);
        delays.push(NodeDelays::symmetric(d / 2, d / 2));
    }
    let disturb = opts.disturb && rng.gen_bool(0.75);
    let mut owned = HashMap::new();
    let mut actions = Vec::new();
    let mut windows = vec![Vec::new(); n];
    // integration: 11 bits after reset, then traffic
    let mut t = 30 * bit_ps + rng.gen_range(0..bit_ps);
    let mut left = opts.frames;
    let disturb_until_frames = opts.frames * 2 / 3;
    let mut quiet_from = t;
    while left > 0 {
        let k = rng.gen_range(1..=n.min(left));
        let mut nodes: Vec<usize> = (0..n).collect();
        for i in 0..k {
            let j = rng.gen_range(i..n);
            nodes.swap(i, j);
        }
        for &node in &nodes[..k] {
            let frame = random_frame(&mut rng, &mut owned, node, n);
            // sometimes another node sends the identical frame at the same instant
            actions.push((t, Action::Request { node, frame }));
        }
        left -= k;
        if disturb && opts.frames - left <= disturb_until_frames {
            let nd = rng.gen_range(0..=2);
            for _ in 0..nd {
                let node = rng.gen_range(0..n);
                let at = t + rng.gen_range(0..150 * bit_ps);
                let kind = rng.gen_range(0..10);
                let (a, len) = match kind {
                    0..=3 => {
                        let len = rng.gen_range(bit_ps / 4..=bit_ps);
                        (Action::Flip { node, len, every: bit_ps, count: 1 }, len)
                    }
                    4..=5 => {
                        let count = rng.gen_range(2..=8);
                        let every = rng.gen_range(bit_ps / 2..=3 * bit_ps);
                        let len = rng.gen_range(bit_ps / 4..=bit_ps);
                        (Action::Flip { node, len, every, count }, every * count as u64)
                    }
                    6..=7 => {
                        let len = rng.gen_range(1..=40) * bit_ps + rng.gen_range(0..bit_ps);
                        (Action::Disturb { node, mode: FaultMode::StuckDominant, len }, len)
                    }
                    _ => {
                        let bits = if rng.gen_bool(0.15) { rng.gen_range(200..=1500) } else { rng.gen_range(1..=40) };
                        let len = bits * bit_ps + rng.gen_range(0..bit_ps);
                        (Action::Disturb { node, mode: FaultMode::StuckRecessive, len }, len)
                    }
                };
                windows[node].push((at, at + len));
                quiet_from = quiet_from.max(at + len);
                actions.push((at, a));
            }
        }
        // gap: 0 (back to back with the previous batch) .. 200 bits, mostly short
        let gap = if rng.gen_bool(0.3) { 0 } else if rng.gen_bool(0.9) { rng.gen_range(0..40) } else { rng.gen_range(40..200) };
        t += gap * bit_ps + rng.gen_range(0..bit_ps);
    }
    actions.sort_by_key(|(t, _)| *t);
    Plan { cfgs, delays, bit_ps, actions, windows, quiet_from }
}

