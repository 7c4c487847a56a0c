use odyn::prelude::*;

#[system(dt = 0.01)]
pub struct Spring {
    #[position]
    pub x: f64,
    #[velocity]
    pub v: f64,
    pub k: f64,
}

#[system]
impl Spring {
    fn acceleration(&self) -> f64 {
        self.x.floor()
    }
}

fn main() {
    let model = Spring { x: 1.0, v: 0.0, k: 1.0 };
    let run = model.simulate().steps(10).run().unwrap();
    let _ = run.last().state.x;
}
