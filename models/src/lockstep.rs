//! Running a compiled model next to its rust-hdl design (driven with
//! `canstar_hdl::drive`) and comparing them: every output on every cycle, every atom
//! of the hierarchy (registers, memories' read registers, combinational signals,
//! constants) on request, with names, so a difference says where.

use canstar_hdl::drive::{self, Clocked};
use canstar_rtlc::rt::{Block, Model};
use rust_hdl::core::prelude::{Atom, Probe, VCDValue};

/// A difference between the two engines.
#[derive(Clone, Debug, PartialEq)]
pub struct Mismatch {
    /// Cycles run before the difference was seen.
    pub cycle: u64,
    pub what: String,
}

impl std::fmt::Display for Mismatch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "after cycle {}: {}", self.cycle, self.what)
    }
}

/// Every atom a block presents to a probe: (dotted path, value).
#[derive(Default)]
pub struct AtomRecorder {
    path: Vec<String>,
    pub atoms: Vec<(String, VCDValue)>,
}

impl Probe for AtomRecorder {
    fn visit_start_scope(&mut self, name: &str, _node: &dyn Block) {
        self.path.push(name.to_string());
    }
    fn visit_start_namespace(&mut self, name: &str, _node: &dyn Block) {
        self.path.push(name.to_string());
    }
    fn visit_atom(&mut self, name: &str, atom: &dyn Atom) {
        self.atoms.push((format!("{}.{}", self.path.join("."), name), atom.vcd()));
    }
    fn visit_end_namespace(&mut self, _name: &str, _node: &dyn Block) {
        self.path.pop();
    }
    fn visit_end_scope(&mut self, _name: &str, _node: &dyn Block) {
        self.path.pop();
    }
}

/// Compare what two probe walks recorded (names, order and values).
pub fn compare_atoms(hdl: &AtomRecorder, model: &AtomRecorder) -> Result<usize, String> {
    if hdl.atoms.len() != model.atoms.len() {
        return Err(format!("{} atoms in the rust-hdl design, {} in the model", hdl.atoms.len(), model.atoms.len()));
    }
    let mut bad = vec![];
    for ((ph, vh), (pm, vm)) in hdl.atoms.iter().zip(&model.atoms) {
        if ph != pm {
            return Err(format!("atom `{ph}` of the rust-hdl design is `{pm}` in the model"));
        }
        if vh != vm {
            bad.push(format!("`{ph}`: rust-hdl {vh:?}, model {vm:?}"));
        }
    }
    if bad.is_empty() {
        Ok(hdl.atoms.len())
    } else {
        Err(format!("{} of {} atoms differ: {}", bad.len(), hdl.atoms.len(), bad.iter().take(8).cloned().collect::<Vec<_>>().join("; ")))
    }
}

/// A rust-hdl design and its compiled model in lock-step.
pub struct Lockstep<H: Clocked, M: Model> {
    pub hdl: H,
    pub model: M,
    set: fn(&mut H, &[u128]),
    get: fn(&H, &mut [u128]),
    pub cycle: u64,
    out_h: Vec<u128>,
    out_m: Vec<u128>,
}

impl<H: Clocked, M: Model> Lockstep<H, M> {
    /// Initialise `hdl` (`drive::init`), build the model from it with `make`
    /// (a generated `from_instance`), and check that both start equal.
    pub fn new(
        mut hdl: H,
        make: fn(&dyn Block) -> Result<M, canstar_rtlc::Error>,
        set: fn(&mut H, &[u128]),
        get: fn(&H, &mut [u128]),
    ) -> Result<Self, Mismatch> {
        drive::init(&mut hdl);
        let model = make(&hdl).map_err(|e| Mismatch { cycle: 0, what: e.to_string() })?;
        let n_out = model.info().outputs.len();
        let mut l = Lockstep { hdl, model, set, get, cycle: 0, out_h: vec![0; n_out], out_m: vec![0; n_out] };
        l.compare_all()?;
        Ok(l)
    }

    /// One clock on both engines with these inputs (model input order); compares
    /// every output.
    pub fn step(&mut self, inputs: &[u128]) -> Result<(), Mismatch> {
        (self.set)(&mut self.hdl, inputs);
        self.model.set_inputs(inputs);
        drive::cycle(&mut self.hdl);
        self.model.cycle();
        self.cycle += 1;
        self.compare_outputs()
    }

    /// Compare the outputs now.
    pub fn compare_outputs(&mut self) -> Result<(), Mismatch> {
        (self.get)(&self.hdl, &mut self.out_h);
        self.model.outputs(&mut self.out_m);
        if self.out_h != self.out_m {
            let info = self.model.info();
            let diffs: Vec<String> = (0..self.out_h.len())
                .filter(|&i| self.out_h[i] != self.out_m[i])
                .map(|i| format!("output `{}`: rust-hdl {:#x}, model {:#x}", info.outputs[i].name, self.out_h[i], self.out_m[i]))
                .collect();
            return Err(Mismatch { cycle: self.cycle, what: diffs.join("; ") });
        }
        Ok(())
    }

    /// The outputs of the last step (model output order).
    pub fn outputs(&self) -> &[u128] {
        &self.out_m
    }

    /// Compare every atom of the hierarchy (the model settles all its signals first).
    pub fn compare_all(&mut self) -> Result<usize, Mismatch> {
        self.model.settle_all();
        let mut h = AtomRecorder::default();
        self.hdl.accept("top", &mut h);
        let mut m = AtomRecorder::default();
        self.model.accept("top", &mut m);
        compare_atoms(&h, &m).map_err(|what| Mismatch { cycle: self.cycle, what })
    }
}

/// Pseudo-random input vectors: each input changes with its own probability per
/// cycle to a uniformly random value of its width.
pub struct RandomInputs {
    rng: rand_chacha::ChaCha8Rng,
    widths: Vec<usize>,
    probs: Vec<f64>,
    pub values: Vec<u128>,
}

impl RandomInputs {
    /// Starting from the model's current inputs; `prob(name)` gives each input's
    /// change probability per cycle.
    pub fn new(model: &dyn Model, seed: u64, prob: impl Fn(&str) -> f64) -> Self {
        use rand::SeedableRng;
        let info = model.info();
        RandomInputs {
            rng: rand_chacha::ChaCha8Rng::seed_from_u64(seed),
            widths: info.inputs.iter().map(|p| p.width).collect(),
            probs: info.inputs.iter().map(|p| prob(p.name)).collect(),
            values: (0..info.inputs.len()).map(|i| model.input(i)).collect(),
        }
    }
    /// The next vector.
    pub fn draw(&mut self) -> &[u128] {
        use rand::Rng;
        for i in 0..self.values.len() {
            if self.rng.gen_bool(self.probs[i]) {
                let v: u128 = self.rng.gen();
                self.values[i] = v & canstar_rtlc::ir::mask(self.widths[i]);
            }
        }
        &self.values
    }
    pub fn rng(&mut self) -> &mut rand_chacha::ChaCha8Rng {
        &mut self.rng
    }
}
