//! The elimination order and the symbolic factorization of a [`BlockPattern`].
//!
//! The order is minimum degree on the node graph with the fill formed explicitly (the graphs
//! are frames: long chains, a few joints, few cycles, so the exact degrees cost little), ties
//! broken by the lowest node index. A node of degree one adds no fill, so a path is eliminated
//! from an end and a tree from its leaves, with no fill and the flops of the block-tridiagonal
//! elimination; a cycle gets one fill edge per elimination (it stays a cycle, one node shorter).
use super::{BlockPattern, Coupling, Step};
use std::collections::BTreeSet;

/// The elimination in the `given` order, or else minimum degree's: the order and, for each
/// node, its neighbours in the filled graph that are eliminated after it (unsorted); and the
/// number of distinct edges given.
fn eliminate(
    nodes: usize,
    edges: &[(usize, usize)],
    given: Option<&[usize]>,
) -> (Vec<usize>, Vec<Vec<usize>>, usize) {
    let mut adjacent: Vec<Vec<usize>> = vec![Vec::new(); nodes];
    for &(i, j) in edges {
        assert!(
            i != j && i < nodes && j < nodes,
            "edge ({i}, {j}) in a pattern of {nodes} nodes"
        );
        adjacent[i].push(j);
        adjacent[j].push(i);
    }
    for list in &mut adjacent {
        list.sort_unstable();
        list.dedup();
    }
    let given_edges = adjacent.iter().map(Vec::len).sum::<usize>() / 2;
    // (degree, node): the first is the minimum degree with the lowest index.
    let mut queue: BTreeSet<(usize, usize)> = match given {
        Some(_) => BTreeSet::new(),
        None => (adjacent.iter().enumerate())
            .map(|(node, list)| (list.len(), node))
            .collect(),
    };
    let mut order = Vec::with_capacity(nodes);
    let mut later = vec![Vec::new(); nodes];
    for k in 0..nodes {
        let node = match given {
            Some(given) => given[k],
            None => queue.pop_first().expect("a node left").1,
        };
        // The lists hold the neighbours not yet eliminated: these are the later ones.
        let neighbours = std::mem::take(&mut adjacent[node]);
        for &u in &neighbours {
            let list = &mut adjacent[u];
            let degree = list.len();
            if let Ok(at) = list.binary_search(&node) {
                list.remove(at);
            }
            // Eliminating `node` couples all its neighbours (the fill).
            for &w in &neighbours {
                if let (true, Err(at)) = (w != u, list.binary_search(&w)) {
                    list.insert(at, w);
                }
            }
            if given.is_none() && list.len() != degree {
                queue.remove(&(degree, u));
                queue.insert((list.len(), u));
            }
        }
        order.push(node);
        later[node] = neighbours;
    }
    (order, later, given_edges)
}

/// The pattern: order (`given`, or minimum degree), steps and slots, Schur targets and each
/// node's couplings.
pub(super) fn symbolic(
    nodes: usize,
    edges: &[(usize, usize)],
    given: Option<&[usize]>,
) -> BlockPattern {
    assert!(nodes >= 1, "a pattern needs a node");
    if let Some(order) = given {
        let mut seen = vec![false; nodes];
        for &node in order {
            assert!(node < nodes && !seen[node], "the order repeats node {node}");
            seen[node] = true;
        }
        assert_eq!(order.len(), nodes, "the order misses nodes");
    }
    let (order, mut later_lists, given) = eliminate(nodes, edges, given);
    let mut position = vec![0; nodes];
    for (k, &node) in order.iter().enumerate() {
        position[node] = k;
    }
    let mut steps = Vec::with_capacity(nodes + 1);
    let mut later = Vec::new();
    let mut slot = 0;
    for &node in order.iter().chain([&nodes]) {
        steps.push(Step {
            node,
            slot,
            later: later.len(),
            targets: 0,
        });
        if node < nodes {
            let mut list = std::mem::take(&mut later_lists[node]);
            list.sort_unstable_by_key(|&q| position[q]);
            slot += 1 + 2 * list.len();
            later.extend(list);
        }
    }
    let filled = later.len();
    let mut pattern = BlockPattern {
        nodes,
        order,
        position,
        steps,
        later,
        targets: Vec::new(),
        couplings: Vec::new(),
        coupling_start: Vec::new(),
        edges: given,
        fill_edges: filled - given,
    };
    let (targets, starts) = schur_targets(&pattern);
    pattern.targets = targets;
    for (step, start) in pattern.steps.iter_mut().zip(starts) {
        step.targets = start;
    }
    (pattern.couplings, pattern.coupling_start) = couplings(&pattern);
    pattern
}

/// For each step, the slots of `(q_a, q_b)` for its later neighbours `q_a`, `q_b` (row-major):
/// present, since eliminating the step's node coupled them. And where each step's targets
/// start, the end last.
fn schur_targets(pattern: &BlockPattern) -> (Vec<usize>, Vec<usize>) {
    let mut targets = Vec::new();
    let mut starts = Vec::with_capacity(pattern.nodes + 1);
    for k in 0..pattern.nodes {
        starts.push(targets.len());
        let later = pattern.later_of(k);
        for &a in later {
            for &b in later {
                targets.push(
                    pattern
                        .slot(a, b)
                        .expect("the fill couples later neighbours"),
                );
            }
        }
    }
    starts.push(targets.len());
    (targets, starts)
}

/// Each node's off-diagonal blocks, grouped by node (`(couplings, start)`).
fn couplings(pattern: &BlockPattern) -> (Vec<Coupling>, Vec<usize>) {
    let n = pattern.nodes;
    let mut start = vec![0; n + 1];
    for k in 0..n {
        start[pattern.order[k] + 1] += pattern.later_of(k).len();
        for &q in pattern.later_of(k) {
            start[q + 1] += 1;
        }
    }
    for i in 0..n {
        start[i + 1] += start[i];
    }
    let mut next = start.clone();
    let placeholder = Coupling {
        node: 0,
        row: 0,
        column: 0,
    };
    let mut couplings = vec![placeholder; start[n]];
    for k in 0..n {
        let (p, slot) = (pattern.order[k], pattern.steps[k].slot);
        for (a, &q) in pattern.later_of(k).iter().enumerate() {
            let (upper, lower) = (slot + 1 + 2 * a, slot + 2 + 2 * a);
            for (i, node, row, column) in [(p, q, upper, lower), (q, p, lower, upper)] {
                couplings[next[i]] = Coupling { node, row, column };
                next[i] += 1;
            }
        }
    }
    (couplings, start)
}
