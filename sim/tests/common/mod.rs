#![allow(dead_code)]
use canstar_sim::{ClockSpec, Component, Io};

/// Test component: on edge `n` records (time, input 0) and, if the script
/// has an entry for `n`, drives output 0.
pub struct Scripted {
    pub name: String,
    pub clock: ClockSpec,
    pub edge: u64,
    pub samples: Vec<(u64, bool)>,
    pub script: Vec<(u64, bool)>,
}

impl Scripted {
    pub fn new(name: &str, clock: ClockSpec, script: &[(u64, bool)]) -> Self {
        Scripted { name: name.into(), clock, edge: 0, samples: Vec::new(), script: script.to_vec() }
    }
}

impl Component for Scripted {
    fn name(&self) -> &str {
        &self.name
    }
    fn clock(&self) -> ClockSpec {
        self.clock
    }
    fn tick(&mut self, io: &mut Io<'_>) {
        if io.n_inputs() > 0 {
            self.samples.push((io.now(), io.input(0)));
        } else {
            self.samples.push((io.now(), true));
        }
        if let Some(&(_, v)) = self.script.iter().find(|e| e.0 == self.edge) {
            io.set_output(0, v);
        }
        self.edge += 1;
    }
}
