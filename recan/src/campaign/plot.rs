//! SVG plot of every controller's TEC and REC over one run, with the instants of hub
//! isolations and controller quarantines marked (vertical lines with labels).
//!
//! The SVG is written as text (no dependency); labels are XML-escaped.

use std::fmt::Write as _;

/// One controller's error counters: (time ps, TEC, REC) samples in time order; the
/// values hold until the next sample.
#[derive(Clone, Debug, Default)]
pub struct Series {
    pub label: String,
    pub points: Vec<(u64, u32, u32)>,
}

/// What a marker marks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MarkerKind {
    Fault,
    Isolation,
    Quarantine,
}

/// A vertical marker at `t_ps`.
#[derive(Clone, Debug)]
pub struct Marker {
    pub t_ps: u64,
    pub kind: MarkerKind,
    pub label: String,
}

/// Everything a plot shows.
#[derive(Clone, Debug, Default)]
pub struct PlotData {
    pub title: String,
    /// Length of the run (x axis end), ps.
    pub end_ps: u64,
    pub series: Vec<Series>,
    pub markers: Vec<Marker>,
}

const W: f64 = 1000.0;
const H: f64 = 520.0;
const L: f64 = 60.0; // plot area left
const R: f64 = 820.0; // plot area right (legend to the right)
const T: f64 = 50.0;
const B: f64 = 470.0;
const COLORS: [&str; 8] = ["#1f77b4", "#2ca02c", "#9467bd", "#8c564b", "#17becf", "#bcbd22", "#e377c2", "#7f7f7f"];

/// XML-escape text for element content and attribute values.
pub fn escape(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    for ch in s.chars() {
        match ch {
            '&' => o.push_str("&amp;"),
            '<' => o.push_str("&lt;"),
            '>' => o.push_str("&gt;"),
            '"' => o.push_str("&quot;"),
            '\'' => o.push_str("&apos;"),
            c => o.push(c),
        }
    }
    o
}

/// Render the plot as a standalone SVG document. The y axis spans 0..=max(128, highest
/// counter) with the error warning limit 96 drawn; TEC is a solid line, REC dashed.
pub fn svg(d: &PlotData) -> String {
    let end = d
        .end_ps
        .max(d.series.iter().flat_map(|s| s.points.last().map(|p| p.0)).max().unwrap_or(0))
        .max(d.markers.iter().map(|m| m.t_ps).max().unwrap_or(0))
        .max(1);
    let ymax = d.series.iter().flat_map(|s| s.points.iter().map(|p| p.1.max(p.2))).max().unwrap_or(0).max(128) as f64;
    let x = |t: u64| L + (R - L) * (t as f64 / end as f64);
    let y = |v: u32| B - (B - T) * (v as f64 / ymax);
    let ms = end as f64 / 1e9;
    let mut s = String::new();
    let _ = writeln!(s, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" viewBox="0 0 {W} {H}" font-family="sans-serif" font-size="11">"#
    );
    let _ = writeln!(s, r#"<rect x="0" y="0" width="{W}" height="{H}" fill="white"/>"#);
    let _ = writeln!(s, r#"<text x="{L}" y="20" font-size="14">{}</text>"#, escape(&d.title));
    // axes and grid
    let _ = writeln!(s, r#"<g id="axes" stroke="black" stroke-width="1">"#);
    let _ = writeln!(s, r#"<line x1="{L}" y1="{B}" x2="{R}" y2="{B}"/><line x1="{L}" y1="{T}" x2="{L}" y2="{B}"/>"#);
    let _ = writeln!(s, "</g>");
    let _ = writeln!(s, r#"<g id="ticks" fill="black">"#);
    for i in 0..=4 {
        let v = (ymax * i as f64 / 4.0).round() as u32;
        let _ = writeln!(s, r#"<text x="{:.1}" y="{:.1}" text-anchor="end">{v}</text>"#, L - 4.0, y(v) + 4.0);
        let t = end / 4 * i;
        let _ = writeln!(s, r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">{:.3}</text>"#, x(t), B + 16.0, t as f64 / 1e9);
    }
    let _ = writeln!(s, r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">time (ms, run length {ms:.3} ms)</text>"#, (L + R) / 2.0, B + 34.0);
    let _ = writeln!(s, "</g>");
    let _ = writeln!(
        s,
        r##"<line id="warning-limit" x1="{L}" y1="{y96:.1}" x2="{R}" y2="{y96:.1}" stroke="#d62728" stroke-width="0.8" stroke-dasharray="2,3"/><text x="{:.1}" y="{:.1}" fill="#d62728">96</text>"##,
        R + 3.0,
        y(96) + 4.0,
        y96 = y(96)
    );
    // series: step lines
    for (i, se) in d.series.iter().enumerate() {
        let col = COLORS[i % COLORS.len()];
        for (k, dash) in [(1usize, ""), (2usize, r#" stroke-dasharray="5,3""#)] {
            // counters are 0 at power-up; each sample holds until the next
            let mut pts = format!("{:.2},{:.2} ", x(0), y(0));
            let mut last = 0u32;
            let mut lx = x(0);
            for &(t, tec, rec) in &se.points {
                let v = if k == 1 { tec } else { rec };
                let xx = x(t);
                if v != last {
                    let _ = write!(pts, "{xx:.2},{:.2} {xx:.2},{:.2} ", y(last), y(v));
                }
                last = v;
                lx = xx;
            }
            {
                let p = last;
                let _ = write!(pts, "{:.2},{:.2}", x(end).max(lx), y(p));
                let _ = writeln!(
                    s,
                    r#"<polyline class="{}" data-ctrl="{}" fill="none" stroke="{col}" stroke-width="1.3"{dash} points="{}"/>"#,
                    if k == 1 { "tec" } else { "rec" },
                    escape(&se.label),
                    pts.trim_end()
                );
            }
        }
        let ly = T + 16.0 * i as f64;
        let _ = writeln!(
            s,
            r#"<g class="legend"><line x1="{:.1}" y1="{ly:.1}" x2="{:.1}" y2="{ly:.1}" stroke="{col}" stroke-width="2"/><text x="{:.1}" y="{:.1}">{}</text></g>"#,
            R + 25.0,
            R + 45.0,
            R + 50.0,
            ly + 4.0,
            escape(&se.label)
        );
    }
    let ly = T + 16.0 * d.series.len() as f64 + 10.0;
    let _ = writeln!(s, r#"<text x="{:.1}" y="{ly:.1}">solid TEC, dashed REC</text>"#, R + 25.0);
    // markers
    for (i, m) in d.markers.iter().enumerate() {
        let (cls, col) = match m.kind {
            MarkerKind::Fault => ("fault", "#000000"),
            MarkerKind::Isolation => ("isolation", "#d62728"),
            MarkerKind::Quarantine => ("quarantine", "#ff7f0e"),
        };
        let xx = x(m.t_ps);
        let ty = T + 12.0 + 12.0 * (i % 8) as f64;
        let _ = writeln!(
            s,
            r##"<g class="marker {cls}"><line x1="{xx:.2}" y1="{T}" x2="{xx:.2}" y2="{B}" stroke="{col}" stroke-width="1" stroke-dasharray="4,2"/><text x="{:.2}" y="{ty:.1}" fill="{col}">{}</text></g>"##,
            xx + 2.0,
            escape(&m.label)
        );
    }
    let _ = writeln!(s, "</svg>");
    s
}
