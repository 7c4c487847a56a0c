use odyn::prelude::*;

// The lowering refuses `is_nan` on the state: one error, at the call, and none at the uses of
// the model's Jacobian below (its stand-in has one).
#[system]
#[derive(Clone, Copy)]
struct Guarded {
    #[state]
    x: f64,
}

#[system]
impl Guarded {
    fn derivative(&self) -> GuardedState {
        GuardedState {
            x: if self.x.is_nan() { 0.0 } else { -self.x },
        }
    }
}

fn main() {
    let model = Guarded { x: 1.0 };
    let y = model.state();
    let mut j = model.jacobian_matrix(&y);
    model.jacobian(0.0, &y, &mut j);
    let _ = j[(0, 0)];
}
