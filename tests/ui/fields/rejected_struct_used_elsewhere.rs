use odyn::prelude::*;

const N: usize = 3;

// The struct is rejected; its impl block and the code that runs it still type-check, so the
// field's error is the only one.
#[system]
pub struct Chain {
    #[state]
    pub x: [f64; N],
    pub k: f64,
}

#[system]
impl Chain {
    fn derivative(&self) -> ChainState {
        ChainState { x: self.x.map(|x| -self.k * x) }
    }
}

fn main() {
    let chain = Chain { x: [1.0; N], k: 1.0 };
    let run = chain.simulate().steps(10).run().unwrap();
    let last: &ChainState = &run.last().state;
    println!("{last:?}");
}
