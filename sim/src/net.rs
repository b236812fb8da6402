//! Nets: driven wires with a transition history and derived wires
//! (delay lines, wired-AND, fault transforms) evaluated lazily by time.
//!
//! Every net carries one bit. Level `false` (0) is **dominant**, `true` (1)
//! is **recessive**, as on a CAN bus. All nets start recessive unless a
//! driven net is created with another initial level.
//!
//! # Time semantics
//! A transition written at time `e` is visible at every instant `x >= e`
//! ([`crate::Sim::value_at`]). A component ticking at its edge `t` samples
//! its inputs *just before* `t` (transitions at times `< t`), as a flip-flop
//! with zero hold time; its outputs then change at `t`. So simultaneous edges
//! of several components never depend on the order they are processed in.
//!
//! A delay line with delay `d` shifts every transition by exactly `d` ps.
//! With separate delays towards dominant (`dD`) and towards recessive
//! (`dR`) it behaves as a driver whose falling edges take `dD` and rising
//! edges `dR`, with short pulses swallowed or stretched as physics does:
//!
//! - `dR >= dD`: `out(t)` is recessive only if `src` was recessive throughout
//!   `[t-dR, t-dD]`. A dominant pulse of width `w` becomes `w + dR - dD`
//!   wide; a recessive pulse of `w <= dR - dD` is swallowed.
//! - `dD > dR`: `out(t)` is dominant only if `src` was dominant throughout
//!   `[t-dD, t-dR]` (the mirror image).
//!
//! Whenever at most one transition falls in such a window this equals
//! `out(t) = src(t-dD) & src(t-dR)` (resp. `|`); for shorter pulses the
//! two-sample formula would split a dominant pulse in two, the window form
//! stretches it.

use std::collections::{BTreeMap, VecDeque};

/// Identifies a net of a [`crate::Sim`].
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct NetId(pub(crate) u32);

impl NetId {
    /// Index of the net in creation order.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// What a fault transform does to its source: the one fault mode of the kernel,
/// used for the receive-path interference of a bus node (the four modes of the
/// Bosch reference CAN bus interface) and for the faults of star links. In files
/// it is written in kebab case (`none`, `invert`, `stuck-recessive`,
/// `stuck-dominant`). For inversion during given time windows only, see
/// [`crate::Sim::add_flip_window`].
#[derive(Copy, Clone, Debug, PartialEq, Eq, Default, serde::Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum FaultMode {
    /// Pass the source unchanged.
    #[default]
    None,
    /// Invert the source.
    Invert,
    /// Output recessive (1) regardless of the source.
    StuckRecessive,
    /// Output dominant (0) regardless of the source.
    StuckDominant,
}

impl FaultMode {
    #[inline]
    fn apply(self, v: bool) -> bool {
        match self {
            FaultMode::None => v,
            FaultMode::Invert => !v,
            FaultMode::StuckRecessive => true,
            FaultMode::StuckDominant => false,
        }
    }
}

pub(crate) enum Node {
    Driven {
        /// Level before the first kept transition.
        base: bool,
        /// Transitions (time, new level), strictly increasing times.
        hist: VecDeque<(u64, bool)>,
        /// Component index that drives this net (at most one).
        driver: Option<usize>,
    },
    Delay {
        src: NetId,
        d_dom: u64,
        d_rec: u64,
    },
    And(Vec<NetId>),
    Fault {
        src: NetId,
        /// Mode before the first kept scheduled change.
        base: FaultMode,
        /// Scheduled changes (time, mode), increasing times.
        sched: VecDeque<(u64, FaultMode)>,
        /// Inversion windows `[start, end)`, sorted, disjoint.
        windows: VecDeque<(u64, u64)>,
    },
}

pub(crate) struct Nets {
    pub(crate) nodes: Vec<Node>,
    pub(crate) names: Vec<String>,
    pub(crate) by_name: BTreeMap<String, NetId>,
    /// Queries before this time may see pruned history.
    pub(crate) pruned_before: u64,
}

impl Nets {
    pub(crate) fn new() -> Self {
        Nets { nodes: Vec::new(), names: Vec::new(), by_name: BTreeMap::new(), pruned_before: 0 }
    }

    pub(crate) fn add(&mut self, name: &str, node: Node) -> NetId {
        assert!(!self.by_name.contains_key(name), "duplicate net name {name:?}");
        if let Node::Delay { src, .. } | Node::Fault { src, .. } = &node {
            assert!(src.index() < self.nodes.len(), "unknown source net");
        }
        if let Node::And(v) = &node {
            assert!(!v.is_empty(), "wired-AND of no nets");
            assert!(v.iter().all(|s| s.index() < self.nodes.len()), "unknown source net");
        }
        let id = NetId(self.nodes.len() as u32);
        self.nodes.push(node);
        self.names.push(name.to_string());
        self.by_name.insert(name.to_string(), id);
        id
    }

    /// Level seen just before `t` (all transitions at times `< t`).
    pub(crate) fn before(&self, id: NetId, t: u64) -> bool {
        match &self.nodes[id.index()] {
            Node::Driven { base, hist, .. } => {
                match hist.back() {
                    None => *base,
                    Some(&(bt, bv)) if bt < t => bv,
                    _ => {
                        debug_assert!(t >= self.pruned_before, "query before pruned history");
                        let i = hist.partition_point(|e| e.0 < t);
                        if i == 0 {
                            *base
                        } else {
                            hist[i - 1].1
                        }
                    }
                }
            }
            &Node::Delay { src, d_dom, d_rec } => {
                if d_dom == d_rec {
                    return self.before(src, t.saturating_sub(d_dom));
                }
                // value at instant x = t-1 depends on src over the window
                // [x - max(dD,dR), x - min(dD,dR)]
                let x = t as i64 - 1;
                let (lo, hi) = (x - d_dom.max(d_rec) as i64, x - d_dom.min(d_rec) as i64);
                if d_rec > d_dom {
                    // recessive only if recessive throughout the window
                    self.all_eq(src, lo, hi, true)
                } else {
                    // dominant only if dominant throughout the window
                    !self.all_eq(src, lo, hi, false)
                }
            }
            Node::And(v) => v.iter().all(|&s| self.before(s, t)),
            Node::Fault { src, base, sched, windows } => {
                let i = sched.partition_point(|e| e.0 < t);
                let mode = if i == 0 { *base } else { sched[i - 1].1 };
                let v = match mode {
                    FaultMode::StuckRecessive => true,
                    FaultMode::StuckDominant => false,
                    m => m.apply(self.before(*src, t)),
                };
                // value_at(x) is inverted for start <= x < end; before(t) = value_at(t-1)
                let w = windows.partition_point(|e| e.0 < t);
                if w > 0 && t <= windows[w - 1].1 {
                    !v
                } else {
                    v
                }
            }
        }
    }

    /// Level at instant `x`, negative instants meaning "before time 0".
    #[inline]
    fn at_i(&self, id: NetId, x: i64) -> bool {
        if x < 0 {
            self.before(id, 0)
        } else {
            self.before(id, x as u64 + 1)
        }
    }

    /// Is `id` at level `v` at every instant of `[lo, hi]`?
    fn all_eq(&self, id: NetId, lo: i64, hi: i64, v: bool) -> bool {
        if self.at_i(id, lo) != v || self.at_i(id, hi) != v {
            return false;
        }
        let mut e = lo;
        while let Some(n) = self.next_event(id, e) {
            if n as i64 >= hi {
                break;
            }
            if self.at_i(id, n as i64) != v {
                return false;
            }
            e = n as i64;
        }
        true
    }

    /// Level at instant `x` (transitions at times `<= x` included).
    pub(crate) fn at(&self, id: NetId, x: u64) -> bool {
        self.before(id, x + 1)
    }

    /// First instant `> after` at which the level may change.
    pub(crate) fn next_event(&self, id: NetId, after: i64) -> Option<u64> {
        match &self.nodes[id.index()] {
            Node::Driven { hist, .. } => {
                let i = hist.partition_point(|e| (e.0 as i64) <= after);
                hist.get(i).map(|e| e.0)
            }
            &Node::Delay { src, d_dom, d_rec } => {
                let a = self.next_event(src, after - d_dom as i64).map(|x| x + d_dom);
                if d_dom == d_rec {
                    return a;
                }
                let b = self.next_event(src, after - d_rec as i64).map(|x| x + d_rec);
                min_opt(a, b)
            }
            Node::And(v) => v.iter().fold(None, |m, &s| min_opt(m, self.next_event(s, after))),
            Node::Fault { src, sched, windows, .. } => {
                let mut m = self.next_event(*src, after);
                let i = sched.partition_point(|e| (e.0 as i64) <= after);
                m = min_opt(m, sched.get(i).map(|e| e.0));
                // windows are disjoint and sorted: their ends are sorted too
                let w = windows.partition_point(|w| (w.1 as i64) <= after);
                if let Some(&(s, e)) = windows.get(w) {
                    m = min_opt(m, Some(if s as i64 > after { s } else { e }));
                }
                m
            }
        }
    }

    /// Record a new level of a driven net at time `t`.
    pub(crate) fn write(&mut self, id: NetId, t: u64, v: bool) {
        match &mut self.nodes[id.index()] {
            Node::Driven { base, hist, .. } => {
                if let Some(&(bt, _)) = hist.back() {
                    assert!(bt <= t, "write into the past of a net");
                    if bt == t {
                        hist.pop_back();
                    }
                }
                let cur = hist.back().map_or(*base, |e| e.1);
                if cur != v {
                    hist.push_back((t, v));
                }
            }
            _ => panic!("net {:?} is not a driven net", self.names[id.index()]),
        }
    }

    pub(crate) fn set_driver(&mut self, id: NetId, comp: usize) {
        match &mut self.nodes[id.index()] {
            Node::Driven { driver, .. } => {
                assert!(driver.is_none(), "net {:?} already has a driver", self.names[id.index()]);
                *driver = Some(comp);
            }
            _ => panic!("output net {:?} is not a driven net", self.names[id.index()]),
        }
    }

    pub(crate) fn driver(&self, id: NetId) -> Option<usize> {
        match &self.nodes[id.index()] {
            Node::Driven { driver, .. } => *driver,
            _ => None,
        }
    }

    pub(crate) fn schedule(&mut self, id: NetId, t: u64, mode: FaultMode) {
        match &mut self.nodes[id.index()] {
            Node::Fault { sched, .. } => {
                let i = sched.partition_point(|e| e.0 < t);
                if i < sched.len() && sched[i].0 == t {
                    sched[i].1 = mode;
                } else {
                    sched.insert(i, (t, mode));
                }
            }
            _ => panic!("net {:?} is not a fault/interference net", self.names[id.index()]),
        }
    }

    /// Drop scheduled changes after `t` (a "set now" overrides the future).
    pub(crate) fn clear_schedule_after(&mut self, id: NetId, t: u64) {
        if let Node::Fault { sched, .. } = &mut self.nodes[id.index()] {
            sched.retain(|e| e.0 <= t);
        }
    }

    pub(crate) fn mode_at(&self, id: NetId, x: u64) -> FaultMode {
        match &self.nodes[id.index()] {
            Node::Fault { base, sched, .. } => {
                let i = sched.partition_point(|e| e.0 <= x);
                if i == 0 {
                    *base
                } else {
                    sched[i - 1].1
                }
            }
            _ => panic!("net {:?} is not a fault/interference net", self.names[id.index()]),
        }
    }

    pub(crate) fn add_window(&mut self, id: NetId, start: u64, end: u64) {
        assert!(start < end, "empty flip window");
        match &mut self.nodes[id.index()] {
            Node::Fault { windows, .. } => {
                // campaigns add windows in time order, thousands per run: append
                // without rebuilding when the new window starts after the last one
                if windows.back().is_none_or(|w| w.1 < start) {
                    windows.push_back((start, end));
                    return;
                }
                let (mut s, mut e) = (start, end);
                let mut kept = VecDeque::with_capacity(windows.len() + 1);
                for &(ws, we) in windows.iter() {
                    if we < s || ws > e {
                        kept.push_back((ws, we));
                    } else {
                        s = s.min(ws);
                        e = e.max(we);
                    }
                }
                let i = kept.partition_point(|w| w.0 < s);
                kept.insert(i, (s, e));
                *windows = kept;
            }
            _ => panic!("net {:?} is not a fault/interference net", self.names[id.index()]),
        }
    }

    /// Largest total delay from any driven net to net `id`.
    pub(crate) fn lookback(&self, id: NetId, memo: &mut Vec<Option<u64>>) -> u64 {
        if let Some(v) = memo[id.index()] {
            return v;
        }
        let v = match &self.nodes[id.index()] {
            Node::Driven { .. } => 0,
            &Node::Delay { src, d_dom, d_rec } => d_dom.max(d_rec) + self.lookback(src, memo),
            Node::And(v) => v.iter().map(|&s| self.lookback(s, memo)).max().unwrap_or(0),
            Node::Fault { src, .. } => self.lookback(*src, memo),
        };
        memo[id.index()] = Some(v);
        v
    }

    pub(crate) fn horizon(&self) -> u64 {
        let mut memo = vec![None; self.nodes.len()];
        (0..self.nodes.len()).map(|i| self.lookback(NetId(i as u32), &mut memo)).max().unwrap_or(0)
    }

    /// Forget history that no query at time `>= cutoff` can need.
    pub(crate) fn prune(&mut self, cutoff: u64) {
        for n in &mut self.nodes {
            match n {
                Node::Driven { base, hist, .. } => {
                    while let Some(&(t, v)) = hist.front() {
                        if t >= cutoff {
                            break;
                        }
                        *base = v;
                        hist.pop_front();
                    }
                }
                Node::Fault { base, sched, windows, .. } => {
                    while let Some(&(t, m)) = sched.front() {
                        if t >= cutoff {
                            break;
                        }
                        *base = m;
                        sched.pop_front();
                    }
                    while windows.front().is_some_and(|w| w.1 < cutoff) {
                        windows.pop_front();
                    }
                }
                _ => {}
            }
        }
        self.pruned_before = self.pruned_before.max(cutoff);
    }

    pub(crate) fn stored_events(&self) -> usize {
        self.nodes
            .iter()
            .map(|n| match n {
                Node::Driven { hist, .. } => hist.len(),
                Node::Fault { sched, windows, .. } => sched.len() + windows.len(),
                _ => 0,
            })
            .sum()
    }
}

#[inline]
fn min_opt(a: Option<u64>, b: Option<u64>) -> Option<u64> {
    match (a, b) {
        (Some(x), Some(y)) => Some(x.min(y)),
        (x, None) => x,
        (None, y) => y,
    }
}
