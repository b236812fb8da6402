//! The sweep classes (`sweep-{point}-{shape}-e{every}`, [`super::classes::Point`],
//! [`super::classes::Shape`]): one disturbance every N bit times at one injection point,
//! from every 2 bits to every 10 000, and the SVG that draws isolation latency and the
//! worst healthy TEC/REC against N ([`svg`], `canstar campaign --plot-sweep F.svg`).
//!
//! Pass criteria are the generic ones of the other classes (no frame lost, no healthy
//! controller at 96, no healthy path isolated); the disturbed path may be isolated.

use super::classes::{ClassKind, Node, Point, Shape, SWEEP_EVERY};
use super::RunOutcome;
use crate::{CtrlRef, Dir, FaultKind, FaultTarget, NetworkSpec};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// Hub clocks per bit of the reference timing (8 TQ of 2 clocks).
const CLOCKS_PER_BIT: f64 = 16.0;

/// The fault kind of `shape` at one disturbance per `every` bit times.
pub fn kind(shape: Shape, every: u32, rng: &mut ChaCha8Rng, net: &NetworkSpec) -> FaultKind {
    let bit_ns = net.bit_time_ps() as f64 / 1000.0;
    let every_bits = every as f64 * rng.gen_range(0.9..1.1);
    let offset_ns = (rng.gen_range(0.0..every_bits.min(200.0)) * bit_ns).round();
    let wide = (bit_ns * rng.gen_range(0.3..1.2)).round();
    match shape {
        Shape::Flip => FaultKind::BitFlip { every_bits, width_ns: wide, offset_ns },
        Shape::D2r => FaultKind::Force { every_bits, width_ns: wide, offset_ns, dominant: false },
        Shape::R2d => FaultKind::Force { every_bits, width_ns: wide, offset_ns, dominant: true },
        Shape::Glitch(w) => FaultKind::BitFlip { every_bits, width_ns: (bit_ns * w as f64 / CLOCKS_PER_BIT).round(), offset_ns },
        Shape::Burst => FaultKind::Burst { every_bits, len_bits: 20.0, flips: 8, seed: rng.gen() },
    }
}

/// The disturbed path of a sweep class: a random node's (Blinker or Receiver) random
/// controller's link, a random sublink, a random interlink or a random hub.
pub fn target(point: Point, rng: &mut ChaCha8Rng) -> FaultTarget {
    match point {
        Point::Up | Point::Down => {
            let node = [Node::Blinker, Node::Receiver][rng.gen_range(0..2)].index();
            let ctrl = [CtrlRef::A, CtrlRef::B][rng.gen_range(0..2usize)];
            FaultTarget::Link { node, ctrl, dir: if point == Point::Up { Dir::Up } else { Dir::Down } }
        }
        Point::Sublink => {
            let (interlink, from_hub) = (rng.gen_range(0..2), rng.gen_range(0..2));
            FaultTarget::Sublink { interlink, from_hub }
        }
        Point::Interlink => FaultTarget::Interlink { interlink: rng.gen_range(0..2) },
        Point::Hub => FaultTarget::Hub { hub: rng.gen_range(0..2) },
    }
}

/// Per (point, shape) series: per interval, (runs, runs with an isolation, median
/// isolation latency, max isolation latency, worst healthy TEC/REC, failures).
type Cell = (u32, u32, Option<u32>, Option<u32>, u32, u32);

fn cells(runs: &[RunOutcome]) -> BTreeMap<String, BTreeMap<u32, Cell>> {
    let mut lat: BTreeMap<(String, u32), Vec<u32>> = BTreeMap::new();
    let mut out: BTreeMap<String, BTreeMap<u32, Cell>> = BTreeMap::new();
    for r in runs {
        let Ok(c) = super::class(&r.class) else { continue };
        let ClassKind::Sweep { point, shape, every } = c.kind else { continue };
        let series = format!("{}-{}", point.name(), shape.name());
        let e = out.entry(series.clone()).or_default().entry(every).or_default();
        e.0 += 1;
        e.4 = e.4.max(r.worst_healthy);
        e.5 += (!r.pass) as u32;
        if let Some(l) = r.isolation_latency_bits {
            e.1 += 1;
            lat.entry((series, every)).or_default().push(l);
        }
    }
    for ((s, every), mut v) in lat {
        v.sort_unstable();
        let e = out.get_mut(&s).and_then(|m| m.get_mut(&every)).expect("cell exists");
        e.2 = Some(v[(v.len() - 1) / 2]);
        e.3 = v.last().copied();
    }
    out
}

/// The sweep table: per series and interval, isolations, median/max latency, worst
/// healthy TEC/REC and failures.
pub fn table(runs: &[RunOutcome]) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "{:<18} {:>6} {:>5} {:>5} {:>13} {:>5} {:>5}", "sweep series", "every", "runs", "iso", "iso bits med/max", "max", "fail");
    for (series, m) in cells(runs) {
        for (every, c) in m {
            let lat = match (c.2, c.3) {
                (Some(a), Some(b)) => format!("{a}/{b}"),
                _ => "-".into(),
            };
            let _ = writeln!(s, "{series:<18} {every:>6} {:>5} {:>5} {lat:>16} {:>5} {:>5}", c.0, c.1, c.4, c.5);
        }
    }
    s
}

const COLORS: [&str; 7] = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#17becf"];

/// SVG: one panel per injection point; in each, per shape, the median isolation latency
/// (solid, left axis, bit times, log scale) and the worst healthy TEC/REC (dashed, right
/// axis, 0..128 with the limit 96 marked) against the interval (log scale).
pub fn svg(runs: &[RunOutcome], title: &str) -> String {
    let data = cells(runs);
    let (pw, ph, ml, mt, gap) = (520.0, 260.0, 70.0, 50.0, 70.0);
    let points = Point::ALL;
    let width = ml + pw + 190.0;
    let height = mt + points.len() as f64 * (ph + gap);
    let mut s = String::new();
    let _ = writeln!(s, r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" font-family="sans-serif" font-size="12">"#);
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/><text x="{ml}" y="24" font-size="15">{}</text>"#, esc(title));
    let lx = |e: f64| (e.log10() - 2f64.log10()) / (10000f64.log10() - 2f64.log10()) * pw;
    let ly = |bits: f64| ph - (bits.max(1.0).log10() / 5.0) * ph; // 1..100 000 bits
    let ty = |v: f64| ph - v / 128.0 * ph;
    for (pi, p) in points.iter().enumerate() {
        let y0 = mt + pi as f64 * (ph + gap);
        let _ = writeln!(s, r#"<g transform="translate({ml},{y0})"><rect width="{pw}" height="{ph}" fill="none" stroke="black"/>"#);
        let _ = writeln!(s, r#"<text x="0" y="-8" font-size="13">{}</text>"#, esc(&format!("injection point: {}", p.name())));
        for e in SWEEP_EVERY {
            let x = lx(e as f64);
            let _ = writeln!(s, r##"<line x1="{x}" y1="0" x2="{x}" y2="{ph}" stroke="#ddd"/><text x="{x}" y="{}" text-anchor="middle">{e}</text>"##, ph + 16.0);
        }
        for k in 0..=5 {
            let y = ly(10f64.powi(k));
            let _ = writeln!(s, r#"<text x="-6" y="{}" text-anchor="end">{}</text>"#, y + 4.0, 10u64.pow(k as u32));
        }
        for v in [0.0, 32.0, 64.0, 96.0, 128.0] {
            let _ = writeln!(s, r#"<text x="{}" y="{}">{v}</text>"#, pw + 6.0, ty(v) + 4.0);
        }
        let _ = writeln!(s, r##"<line x1="0" y1="{0}" x2="{pw}" y2="{0}" stroke="#d62728" stroke-dasharray="2,4"/>"##, ty(96.0));
        let _ = writeln!(s, r#"<text x="{}" y="{}" text-anchor="middle">disturbance every N bit times</text>"#, pw / 2.0, ph + 34.0);
        let _ = writeln!(s, r#"<text transform="translate(-50,{}) rotate(-90)" text-anchor="middle">isolation latency (bits, median)</text>"#, ph / 2.0);
        let _ = writeln!(s, r#"<text transform="translate({},{}) rotate(90)" text-anchor="middle">worst healthy TEC/REC (dashed)</text>"#, pw + 40.0, ph / 2.0);
        for (si, shape) in Shape::ALL.iter().enumerate() {
            let name = format!("{}-{}", p.name(), shape.name());
            let col = COLORS[si % COLORS.len()];
            let _ = writeln!(s, r#"<text x="{}" y="{}" fill="{col}">{}</text>"#, pw + 70.0, 14.0 + si as f64 * 16.0, esc(&shape.name()));
            let Some(m) = data.get(&name) else { continue };
            let lat: Vec<String> = m.iter().filter_map(|(&e, c)| c.2.map(|l| format!("{:.1},{:.1}", lx(e as f64), ly(l as f64)))).collect();
            let tec: Vec<String> = m.iter().map(|(&e, c)| format!("{:.1},{:.1}", lx(e as f64), ty(c.4 as f64))).collect();
            if !lat.is_empty() {
                let _ = writeln!(s, r#"<polyline points="{}" fill="none" stroke="{col}" stroke-width="2"/>"#, lat.join(" "));
            }
            let _ = writeln!(s, r#"<polyline points="{}" fill="none" stroke="{col}" stroke-dasharray="5,3"/>"#, tec.join(" "));
            for (&e, c) in m {
                if c.5 > 0 {
                    let _ = writeln!(s, r#"<text x="{:.1}" y="{:.1}" fill="{col}" text-anchor="middle">✗</text>"#, lx(e as f64), ty(c.4 as f64) - 4.0);
                }
            }
        }
        let _ = writeln!(s, "</g>");
    }
    let _ = writeln!(s, "</svg>");
    s
}

fn esc(t: &str) -> String {
    t.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(class: &str, pass: bool, worst: u32, lat: Option<u32>) -> RunOutcome {
        RunOutcome { class: class.into(), pass, worst_healthy: worst, isolation_latency_bits: lat, ..Default::default() }
    }

    #[test]
    fn cells_aggregate_per_series_and_interval() {
        let runs = vec![
            run("sweep-up-flip-e10", true, 40, Some(30)),
            run("sweep-up-flip-e10", false, 99, Some(50)),
            run("sweep-up-flip-e10", true, 10, None),
            run("sweep-up-flip-e100", true, 8, Some(700)),
            run("flip-receiver-tx-up-r100", true, 1, Some(1)),
        ];
        let c = cells(&runs);
        assert_eq!(c.len(), 1, "only sweep classes");
        assert_eq!(c["up-flip"][&10], (3, 2, Some(30), Some(50), 99, 1));
        assert_eq!(c["up-flip"][&100], (1, 1, Some(700), Some(700), 8, 0));
        let svg = svg(&runs, "t <1>");
        assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
        assert!(svg.contains("t &lt;1&gt;") && svg.contains("polyline") && svg.contains('✗'));
        assert!(table(&runs).contains("up-flip"));
    }

    #[test]
    fn every_sweep_class_builds_its_fault() {
        use rand::SeedableRng;
        let net = NetworkSpec::fast();
        for c in super::super::classes::catalogue() {
            let ClassKind::Sweep { point, shape, every } = c.kind else { continue };
            let mut rng = ChaCha8Rng::seed_from_u64(7);
            let t = target(point, &mut rng);
            let ok = matches!(
                (point, t),
                (Point::Up, FaultTarget::Link { dir: Dir::Up, .. })
                    | (Point::Down, FaultTarget::Link { dir: Dir::Down, .. })
                    | (Point::Sublink, FaultTarget::Sublink { .. })
                    | (Point::Interlink, FaultTarget::Interlink { .. })
                    | (Point::Hub, FaultTarget::Hub { .. })
            );
            assert!(ok, "{}: {t:?}", c.name);
            match (shape, kind(shape, every, &mut rng, &net)) {
                (Shape::Glitch(w), FaultKind::BitFlip { width_ns, .. }) => {
                    let clocks = width_ns / (net.bit_time_ps() as f64 / 1000.0 / CLOCKS_PER_BIT);
                    assert!((clocks - w as f64).abs() < 0.5, "{}: {clocks}", c.name);
                }
                (Shape::R2d, FaultKind::Force { dominant, .. }) => assert!(dominant),
                (Shape::D2r, FaultKind::Force { dominant, .. }) => assert!(!dominant),
                (Shape::Flip, FaultKind::BitFlip { .. }) | (Shape::Burst, FaultKind::Burst { .. }) => {}
                (s, k) => panic!("{}: {s:?} built {k:?}", c.name),
            }
        }
    }
}
