//! A worker's numbering of a few of a mesh's vertices (a patch's, in its own numbering),
//! kept from patch to patch: started again at no cost, without a pass over the slots.

thread_local! {
    /// Each worker's numbering of a patch's vertices (see [`Numbering`]).
    pub(super) static NUMBERING: std::cell::RefCell<Numbering> = const { std::cell::RefCell::new(Numbering { round: 0, slots: Vec::new() }) };
}

/// A numbering of some of M1's vertices, kept by a worker from patch to patch: each slot
/// holds the round it was set in (high word) and the number (low word), so that starting a
/// new numbering forgets the last at once, without a pass over the slots.
pub(super) struct Numbering {
    round: u32,
    slots: Vec<u64>,
}

impl Numbering {
    /// A new numbering of `n` vertices, none numbered.
    pub(super) fn start(&mut self, n: usize) -> &mut Self {
        self.round = self.round.wrapping_add(1);
        if self.round == 0 {
            // The rounds went round: no slot may hold a round still to come.
            self.slots.fill(0);
            self.round = 1;
        }
        if self.slots.len() < n {
            self.slots.resize(n, 0);
        }
        self
    }

    /// Vertex `v`'s number, if numbered.
    pub(super) fn get(&self, v: u32) -> Option<u32> {
        let slot = self.slots[v as usize];
        ((slot >> 32) as u32 == self.round).then_some(slot as u32)
    }

    /// Numbers vertex `v`.
    pub(super) fn set(&mut self, v: u32, number: u32) {
        self.slots[v as usize] = (u64::from(self.round) << 32) | u64::from(number);
    }
}

#[cfg(test)]
mod tests {
    use super::Numbering;

    /// A numbering started again forgets the last one, also when its rounds go round: a
    /// slot set in the last round before the count wraps must not read as set after it.
    #[test]
    fn a_new_numbering_forgets_the_last_also_when_the_rounds_wrap() {
        let mut numbering = Numbering {
            round: 0,
            slots: Vec::new(),
        };
        let local = numbering.start(5);
        local.set(3, 7);
        assert_eq!((local.get(3), local.get(2)), (Some(7), None));
        assert_eq!(numbering.start(5).get(3), None);
        // The last round before the count wraps, then the first after.
        numbering.round = u32::MAX - 1;
        let local = numbering.start(5);
        local.set(1, 9);
        assert_eq!(local.get(1), Some(9));
        let local = numbering.start(8);
        assert_eq!((0..8).filter_map(|v| local.get(v)).count(), 0);
        local.set(6, 2);
        assert_eq!(local.get(6), Some(2));
    }
}
