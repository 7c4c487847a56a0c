//! [`Fingerprint`]: a 64-bit hash of every bit of a run, to compare two runs — on two machines,
//! natively and in a browser — without shipping their states.

use crate::{State, Trajectory};

/// FNV-1a (64-bit) over the IEEE bits of `f64`s: Fowler, Noll & Vo's hash with its 64-bit offset
/// basis 0xcbf29ce484222325 and prime 0x100000001b3 (IETF draft-eastlake-fnv, §2).
///
/// Not cryptographic: it tells two runs apart when one last bit of one number differs (the
/// tests show it), which is what comparing runs across platforms needs. With odyn's
/// `deterministic` feature the same run gives the same fingerprint on x86-64 and WebAssembly
/// (the guide's chapter *Determinism and the browser lab*).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Fingerprint(u64);

impl Default for Fingerprint {
    fn default() -> Self {
        Fingerprint(0xcbf2_9ce4_8422_2325)
    }
}

impl Fingerprint {
    /// The hash of nothing yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds one number's eight bytes (little-endian bits: the same on every platform).
    pub fn add(&mut self, x: f64) {
        for byte in x.to_bits().to_le_bytes() {
            self.0 = (self.0 ^ u64::from(byte)).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }

    /// Adds every number of `xs`, in order.
    pub fn extend<'a>(&mut self, xs: impl IntoIterator<Item = &'a f64>) {
        for &x in xs {
            self.add(x);
        }
    }

    /// The hash so far.
    pub fn finish(&self) -> u64 {
        self.0
    }

    /// A trajectory's fingerprint: every sample's time and state, then every event's time and
    /// states before and after, in order.
    pub fn of_trajectory<S: State>(run: &Trajectory<S>) -> u64 {
        let mut hash = Fingerprint::new();
        for sample in &run.samples {
            hash.add(sample.t);
            hash.extend(sample.state.as_slice());
        }
        for event in &run.events {
            hash.add(event.t);
            hash.extend(event.before.as_slice());
            hash.extend(event.after.as_slice());
        }
        hash.finish()
    }
}

#[cfg(test)]
mod tests {
    use super::Fingerprint;

    /// The published FNV-1a 64 test vector: "a" hashes to 0xaf63dc4c8601ec8c
    /// (draft-eastlake-fnv, appendix C). One f64 is eight bytes; hashing the byte alone checks
    /// the constants.
    #[test]
    fn the_constants_are_fnv_1a_64() {
        let mut hash = Fingerprint::new();
        hash.0 = (hash.0 ^ u64::from(b'a')).wrapping_mul(0x0000_0100_0000_01b3);
        assert_eq!(hash.finish(), 0xaf63_dc4c_8601_ec8c);
    }

    /// One ulp in one number changes the hash.
    #[test]
    fn one_bit_changes_the_hash() {
        let (mut a, mut b) = (Fingerprint::new(), Fingerprint::new());
        a.extend(&[1.0, 2.0]);
        b.extend(&[1.0, f64::from_bits(2.0f64.to_bits() + 1)]);
        assert_ne!(a.finish(), b.finish());
    }
}
