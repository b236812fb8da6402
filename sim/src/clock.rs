//! Clocks of components: period, oscillator offset, phase and jitter, with exact
//! integer edge times.

/// Clock of one component: nominal period in ps, oscillator offset and
/// start phase.
///
/// Rising edge `n` (from 0) is at
/// `phase_ps + floor(n * period_ps * (1e9 + ppb) / 1e9)`, computed in
/// integers, so edge times are exact and never accumulate rounding error.
/// The offset is stored in parts per billion (ppm are rounded to 0.001 ppm).
///
/// Optional jitter: in a [`Sim`], every edge is delayed by a random
/// `0..=jitter_ps` ps drawn from a per-component generator derived from the
/// simulation seed and the component index (non-accumulating: the nominal
/// edge times above stay the reference).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct ClockSpec {
    pub period_ps: u64,
    /// Oscillator offset in parts per billion (positive = slower clock).
    pub ppb: i64,
    /// Time of edge 0.
    pub phase_ps: u64,
    /// Maximum random delay of each edge (0 = none).
    pub jitter_ps: u64,
}

impl ClockSpec {
    /// A clock with the given nominal period, no offset, edge 0 at time 0.
    pub fn new(period_ps: u64) -> Self {
        assert!(period_ps > 0, "clock period must be positive");
        ClockSpec { period_ps, ppb: 0, phase_ps: 0, jitter_ps: 0 }
    }
    /// A clock of `mhz` MHz (period rounded to the picosecond).
    pub fn mhz(mhz: f64) -> Self {
        Self::new((1e6 / mhz).round() as u64)
    }
    /// Oscillator offset in ppm: the period is `period_ps * (1 + ppm * 1e-6)`
    /// (positive ppm = slower clock).
    pub fn with_ppm(mut self, ppm: f64) -> Self {
        self.ppb = (ppm * 1000.0).round() as i64;
        assert!(self.ppb > -1_000_000_000, "offset must be above -1e6 ppm");
        self
    }
    /// Time of edge 0.
    pub fn with_phase(mut self, phase_ps: u64) -> Self {
        self.phase_ps = phase_ps;
        self
    }
    /// Random delay of up to `jitter_ps` on every edge (less than half a period).
    pub fn with_jitter(mut self, jitter_ps: u64) -> Self {
        assert!(jitter_ps * 2 < self.period_ps, "jitter must stay below half a period");
        self.jitter_ps = jitter_ps;
        self
    }
    /// Nominal time of rising edge `n` (without jitter).
    #[inline]
    pub fn edge_time(&self, n: u64) -> u64 {
        // phase + floor(n * period * (1e9 + ppb) / 1e9) = phase + a + floor(a * ppb / 1e9)
        // with a = n * period; in 64 bits when that fits (the usual case), else 128
        const G: u64 = 1_000_000_000;
        if let Some(a) = n.checked_mul(self.period_ps) {
            if let Some(m) = a.checked_mul(self.ppb.unsigned_abs()) {
                return self.phase_ps + if self.ppb >= 0 { a + m / G } else { a - m.div_ceil(G) };
            }
        }
        let scaled = n as u128 * self.period_ps as u128 * (1_000_000_000i64 + self.ppb) as u128;
        self.phase_ps + (scaled / 1_000_000_000u128) as u64
    }
    /// Index of the first edge at a time `> t`.
    pub fn first_edge_after(&self, t: u64) -> u64 {
        if t < self.phase_ps {
            return 0;
        }
        let eff = self.period_ps as f64 * (1.0 + self.ppb as f64 * 1e-9);
        let mut n = ((t - self.phase_ps) as f64 / eff) as u64;
        while n > 0 && self.edge_time(n - 1) > t {
            n -= 1;
        }
        while self.edge_time(n) <= t {
            n += 1;
        }
        n
    }
}


#[cfg(test)]
mod tests {
    use super::*;

    /// The 64-bit path gives the exact 128-bit floor, for offsets of both signs.
    #[test]
    fn edge_time_is_the_exact_floor() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        for _ in 0..100_000 {
            let c = ClockSpec::new(rng.gen_range(1..200_000)).with_ppm(rng.gen_range(-500.0..500.0)).with_phase(rng.gen_range(0..1000));
            let n = if rng.gen_bool(0.5) { rng.gen_range(0..1u64 << 20) } else { rng.gen_range(0..1u64 << 40) };
            let exact = c.phase_ps + (n as u128 * c.period_ps as u128 * (1_000_000_000i64 + c.ppb) as u128 / 1_000_000_000) as u64;
            assert_eq!(c.edge_time(n), exact, "{c:?} n {n}");
        }
    }
}
