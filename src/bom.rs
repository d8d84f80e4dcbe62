//! Bill of materials: how many of each physical part a chain needs.

use std::collections::BTreeMap;

use crate::{Chain, Part};

/// Count per physical part, in the order SS, RS, SR, RR, LR, RL; parts not used are left out.
#[derive(Clone, Debug, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
pub struct BillOfMaterials {
    /// Parts and their counts.
    pub parts: BTreeMap<Part, usize>,
}

impl BillOfMaterials {
    /// The parts a chain needs (a tile turned round is the same part).
    pub fn from_chain(chain: &Chain) -> BillOfMaterials {
        let mut parts = BTreeMap::new();
        for t in chain.tiles() {
            *parts.entry(t.part()).or_insert(0) += 1;
        }
        BillOfMaterials { parts }
    }

    /// The count of one part.
    pub fn count(&self, part: Part) -> usize {
        self.parts.get(&part).copied().unwrap_or(0)
    }

    /// The total number of tiles.
    pub fn total(&self) -> usize {
        self.parts.values().sum()
    }
}

impl std::fmt::Display for BillOfMaterials {
    /// `SS x12, RS x2, RR x1`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        for (i, (part, n)) in self.parts.iter().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            write!(f, "{part} x{n}")?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parts_of_a_u_turn() {
        let c = Chain::parse("SLLS").unwrap(); // SS SL LL LS SS
        let b = BillOfMaterials::from_chain(&c);
        assert_eq!(b.count(Part::SS), 2);
        assert_eq!(b.count(Part::RS), 1);
        assert_eq!(b.count(Part::SR), 1);
        assert_eq!(b.count(Part::RR), 1);
        assert_eq!(b.total(), 5);
        assert_eq!(b.to_string(), "SS x2, RS x1, SR x1, RR x1");
    }
}
