//! A chain with leaf bodies: the shape of most published arms (a serial chain, and fingers or
//! tool bodies that carry nothing), found once when the model is built, for CRBA's pass that
//! carries the chain's composite inertia in registers.

/// A body that has no children and is not on the [`Spine`]: its parent is a spine body or the
/// base.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Leaf {
    /// The leaf body.
    pub body: usize,
    /// Its parent `λ(body)` (a spine body), `None` on the base.
    pub parent: Option<usize>,
}

/// The bodies `start..end` form a chain (`λ(start) = None`, `λ(i) = i − 1` after it) and every
/// other body is a [`Leaf`] on the base or on that chain. A model whose bodies are all on the
/// spine (`start = 0`, `end = n`, no leaves) is a chain.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct Spine {
    /// The first spine body.
    pub start: usize,
    /// One past the last spine body.
    pub end: usize,
    /// The other bodies, in the order CRBA meets them from the chain's end: by decreasing
    /// parent, the leaves of one parent by increasing index, the leaves on the base last.
    pub leaves: Vec<Leaf>,
}

impl Spine {
    /// The spine of the tree given by each body's parent (`parents[i] < i`), or `None` when the
    /// bodies that have children do not form one chain of consecutive indices. The chain runs
    /// from the first body with children to the last, plus the last one's child right after it
    /// (a leaf carried on the chain costs less than a leaf apart); with no body having
    /// children, it is body 0 alone.
    pub fn find(parents: &[Option<usize>]) -> Option<Spine> {
        let n = parents.len();
        if n == 0 {
            return None;
        }
        let mut has_children = vec![false; n];
        for p in parents.iter().flatten() {
            has_children[*p] = true;
        }
        let (start, end) = match (
            has_children.iter().position(|&c| c),
            has_children.iter().rposition(|&c| c),
        ) {
            (Some(first), Some(last)) => {
                if (first + 1..=last).any(|i| parents[i] != Some(i - 1)) {
                    return None;
                }
                let extend = last + 1 < n && parents[last + 1] == Some(last);
                (first, last + 1 + usize::from(extend))
            }
            _ => (0, 1),
        };
        let mut leaves: Vec<Leaf> = (0..n)
            .filter(|i| !(start..end).contains(i))
            .map(|body| Leaf {
                body,
                parent: parents[body],
            })
            .collect();
        // (A stable sort: one parent's leaves keep their order; `None` sorts first, so last.)
        leaves.sort_by_key(|l| std::cmp::Reverse(l.parent));
        Some(Spine { start, end, leaves })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn leaf(body: usize, parent: Option<usize>) -> Leaf {
        Leaf { body, parent }
    }

    #[test]
    fn chains_arms_with_fingers_and_leaves_on_the_base() {
        // A chain: everything on the spine.
        let s = Spine::find(&[None, Some(0), Some(1)]).unwrap();
        assert_eq!((s.start, s.end, s.leaves.len()), (0, 3, 0));
        // The Panda: seven arm bodies, two fingers on body 6; the first finger ends the spine.
        let panda = [
            None,
            Some(0),
            Some(1),
            Some(2),
            Some(3),
            Some(4),
            Some(5),
            Some(6),
            Some(6),
        ];
        let s = Spine::find(&panda).unwrap();
        assert_eq!((s.start, s.end), (0, 8));
        assert_eq!(s.leaves, vec![leaf(8, Some(6))]);
        // A leaf on the base first, the chain after it, three leaves on one body and one on
        // another (depth-first order: a leaf's index follows its parent's subtree).
        let parents = [
            None,
            None,
            Some(1),
            Some(2),
            Some(2),
            Some(2),
            Some(1),
            None,
        ];
        let s = Spine::find(&parents).unwrap();
        assert_eq!((s.start, s.end), (1, 4));
        assert_eq!(
            s.leaves,
            vec![
                leaf(4, Some(2)),
                leaf(5, Some(2)),
                leaf(6, Some(1)),
                leaf(0, None),
                leaf(7, None),
            ]
        );
        // Bodies all on the base: body 0 is the spine.
        let s = Spine::find(&[None, None]).unwrap();
        assert_eq!((s.start, s.end), (0, 1));
        assert_eq!(s.leaves, vec![leaf(1, None)]);
    }

    #[test]
    fn branches_with_children_are_no_spine() {
        // Two bodies with children on different branches.
        assert_eq!(
            Spine::find(&[None, Some(0), Some(0), Some(1), Some(2)]),
            None
        );
        // Two chains on the base.
        assert_eq!(Spine::find(&[None, Some(0), None, Some(2)]), None);
        assert_eq!(Spine::find(&[]), None);
    }
}
