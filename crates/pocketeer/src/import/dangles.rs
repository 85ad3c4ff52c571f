//! Strokes that bound nothing: a chain of elements between a free end or a branch (three or
//! more ends meeting) and another branch, whose removal would split the drawing's graph in two
//! (a bridge of the graph). A construction line ending on the outline, a leader drawn from a
//! hole to a corner, a centre line to the wall: left in, each makes a branch where the
//! chaining must guess which way the outline goes. They are taken out, and reported; chains
//! from a free end to a free end stay, as the open chains they are.

use super::chain::End;
use super::nodes::Nodes;
use crate::geom::Point;

/// A stroke taken out: how many elements, and its two ends (a free end or a branch first,
/// the branch it meets last).
#[derive(Debug, Clone, Copy)]
pub(super) struct Dangle {
    pub(super) elements: usize,
    pub(super) from: Point,
    pub(super) to: Point,
}

/// A chain between two junctions (nodes where other than two ends meet).
pub(super) struct Stroke {
    /// Its elements in order from `ends[0]`, each with whether it runs backwards.
    pub(super) elements: Vec<(usize, bool)>,
    /// The junctions it starts and ends at.
    pub(super) ends: [usize; 2],
}

/// The chains of live elements between junctions, and every node's degree.
pub(super) struct Strokes {
    pub(super) strokes: Vec<Stroke>,
    pub(super) degree: Vec<usize>,
}

/// Marks dead every live element on a bridge chain that touches a branch, repeating while
/// taking some out makes others bridges; returns the strokes taken out, and the strokes left.
pub(super) fn remove_dangles(alive: &mut [bool], nodes: &Nodes) -> (Vec<Dangle>, Strokes) {
    let mut dangles = Vec::new();
    loop {
        let (strokes, degree) = strokes(alive, nodes);
        let bridges = bridges(&strokes, nodes.pos.len());
        let mut removed = false;
        for (k, s) in strokes.iter().enumerate() {
            let [a, b] = s.ends;
            if bridges[k] && (degree[a] >= 3 || degree[b] >= 3) {
                for &(i, _) in &s.elements {
                    alive[i] = false;
                }
                let (from, to) = if degree[a] >= 3 { (b, a) } else { (a, b) };
                dangles.push(Dangle {
                    elements: s.elements.len(),
                    from: nodes.pos[from],
                    to: nodes.pos[to],
                });
                removed = true;
            }
        }
        if !removed {
            return (dangles, Strokes { strokes, degree });
        }
    }
}

/// The chains of live elements between junctions, and every node's degree. Loops through
/// two-ended nodes only are no strokes and are left out.
fn strokes(alive: &[bool], nodes: &Nodes) -> (Vec<Stroke>, Vec<usize>) {
    let mut at_node: Vec<Vec<End>> = vec![Vec::new(); nodes.pos.len()];
    for i in (0..alive.len()).filter(|&i| alive[i]) {
        for end in [0u8, 1] {
            at_node[nodes.node((i, end))].push((i, end));
        }
    }
    let degree: Vec<usize> = at_node.iter().map(Vec::len).collect();
    let mut used = vec![false; alive.len()];
    let mut strokes = Vec::new();
    for (start, ends) in at_node.iter().enumerate() {
        if degree[start] == 2 {
            continue;
        }
        for &(first, first_end) in ends {
            if used[first] {
                continue;
            }
            used[first] = true;
            let mut elements = vec![(first, first_end == 1)];
            let mut at: End = (first, 1 - first_end);
            loop {
                let n = nodes.node(at);
                if degree[n] != 2 {
                    strokes.push(Stroke {
                        elements,
                        ends: [start, n],
                    });
                    break;
                }
                let &(j, e) = at_node[n].iter().find(|&&e| e != at).unwrap_or(&at);
                if used[j] {
                    break;
                }
                used[j] = true;
                elements.push((j, e == 1));
                at = (j, 1 - e);
            }
        }
    }
    (strokes, degree)
}

/// Which strokes are bridges of the multigraph they form on `nodes` nodes: no cycle passes
/// through them. Depth-first search with low links, without recursion (drawings have chains
/// of thousands of junctions).
fn bridges(strokes: &[Stroke], nodes: usize) -> Vec<bool> {
    let mut adjacent: Vec<Vec<(usize, usize)>> = vec![Vec::new(); nodes];
    for (k, s) in strokes.iter().enumerate() {
        adjacent[s.ends[0]].push((s.ends[1], k));
        adjacent[s.ends[1]].push((s.ends[0], k));
    }
    let mut order = vec![usize::MAX; nodes];
    let mut low = vec![0usize; nodes];
    let mut bridge = vec![false; strokes.len()];
    let mut counter = 0;
    for root in 0..nodes {
        if order[root] != usize::MAX || adjacent[root].is_empty() {
            continue;
        }
        // (node, the stroke it was reached by, next neighbour to look at)
        let mut stack: Vec<(usize, usize, usize)> = vec![(root, usize::MAX, 0)];
        order[root] = counter;
        low[root] = counter;
        counter += 1;
        while let Some(&mut (v, via, ref mut next)) = stack.last_mut() {
            if let Some(&(w, k)) = adjacent[v].get(*next) {
                *next += 1;
                if k == via {
                    continue;
                }
                if order[w] == usize::MAX {
                    order[w] = counter;
                    low[w] = counter;
                    counter += 1;
                    stack.push((w, k, 0));
                } else {
                    low[v] = low[v].min(order[w]);
                }
            } else {
                stack.pop();
                if let Some(&(parent, _, _)) = stack.last() {
                    low[parent] = low[parent].min(low[v]);
                    if low[v] > order[parent] {
                        bridge[via] = true;
                    }
                }
            }
        }
    }
    bridge
}
