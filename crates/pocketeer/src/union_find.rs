//! Disjoint sets over `0..n` (union–find with path halving): which end points are one node,
//! which contours touch, which pieces form one run.

/// Disjoint sets of the integers `0..len`.
#[derive(Debug, Clone)]
pub struct UnionFind {
    parent: Vec<usize>,
}

impl UnionFind {
    /// `n` singleton sets.
    pub fn new(n: usize) -> UnionFind {
        UnionFind {
            parent: (0..n).collect(),
        }
    }

    /// Adds a singleton set and returns its element.
    pub fn add(&mut self) -> usize {
        self.parent.push(self.parent.len());
        self.parent.len() - 1
    }

    /// The representative of `x`'s set (the smallest element ever united into it is not
    /// guaranteed; the representative is stable until the next union).
    pub fn find(&mut self, mut x: usize) -> usize {
        while self.parent[x] != x {
            self.parent[x] = self.parent[self.parent[x]];
            x = self.parent[x];
        }
        x
    }

    /// Unites the sets of `a` and `b`.
    pub fn union(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.parent[ra.max(rb)] = ra.min(rb);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unions_are_transitive() {
        let mut u = UnionFind::new(5);
        u.union(0, 3);
        u.union(3, 4);
        assert_eq!(u.find(4), u.find(0));
        assert_ne!(u.find(1), u.find(0));
        let x = u.add();
        assert_eq!(u.find(x), x);
    }
}
