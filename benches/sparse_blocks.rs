//! Cost of the sparse block solver against the number of nodes, and against the
//! block-tridiagonal solver on a chain: prints microseconds per factorization (`copy_from` +
//! `factor_symmetric`) and per solve (`solve_in_place`) for 10 to 10,000 nodes, on a chain (in
//! the minimum-degree order, from one end, and in the twisted order of `BlockTridiagonal`), a
//! closed loop of four member chains (one fill edge per elimination) and a tree of member
//! chains, the ratio sparse / tridiagonal on the chains and the ratio of the cost per node to
//! the previous size's (1.0: linear).
//!
//! Run: `cargo bench --bench sparse_blocks` (release profile). Each time is the best of 41
//! rounds of at least 0.5 ms each, the two solvers' rounds interleaved. What to expect: a chain
//! eliminated from one end is one dependency chain (each step waits for the one before), the
//! twisted order two side by side, so the first is slower by the latency, mostly in the solve;
//! at 10,000 nodes the blocks (2 MB) leave the L2 cache; the loop's fill couplings decay along
//! the members and pass through subnormal numbers (slow arithmetic) for a few dozen steps per
//! member, which shows at 1000 nodes (at 10,000 they have reached zero).
use georod::solver::{BlockPattern, BlockTridiagonal, SparseBlocks};
use nalgebra::Matrix3;
use std::hint::black_box;
use std::sync::Arc;
use std::time::Instant;

/// Seconds per call of each closure: the best of 41 rounds of at least half a millisecond
/// (short enough to run between two preemptions on a loaded machine), the closures' rounds
/// interleaved so that a load that comes and goes slows them alike.
fn best_times<const K: usize>(fs: &mut [&mut dyn FnMut(); K]) -> [f64; K] {
    let mut reps = [1usize; K];
    for (f, r) in fs.iter_mut().zip(&mut reps) {
        loop {
            let start = Instant::now();
            (0..*r).for_each(|_| f());
            if start.elapsed().as_secs_f64() > 5e-4 {
                break;
            }
            *r *= 2;
        }
    }
    let mut best = [f64::INFINITY; K];
    for _ in 0..41 {
        for ((f, r), b) in fs.iter_mut().zip(&reps).zip(&mut best) {
            let start = Instant::now();
            (0..*r).for_each(|_| f());
            *b = b.min(start.elapsed().as_secs_f64() / *r as f64);
        }
    }
    best
}

/// A chain's, a closed loop's (4 corners 0..4, then the members' inner nodes) or a tree's
/// (members of 10 nodes, each hung from a node of an earlier one) edges, and its node count.
fn graph(kind: &str, n: usize) -> (usize, Vec<(usize, usize)>) {
    let chain = |first: usize, len: usize| (first + 1..first + len).map(|i| (i - 1, i));
    match kind {
        "chain" | "twisted chain" => (n, chain(0, n).collect()),
        "loop" => {
            let inner = n / 4 - 1;
            let mut edges = Vec::new();
            for k in 0..4 {
                let first = 4 + k * inner;
                edges.extend(chain(first, inner));
                edges.extend([(k, first), (first + inner - 1, (k + 1) % 4)]);
            }
            (4 + 4 * inner, edges)
        }
        _ => {
            let members = n / 10;
            let mut edges: Vec<_> = chain(0, 10).collect();
            for m in 1..members {
                edges.extend(chain(10 * m, 10));
                edges.push(((7919 * m) % (10 * m), 10 * m));
            }
            (10 * members, edges)
        }
    }
}

/// An element's symmetric blocks: a stiffness-like coupling, diagonally dominant with the
/// diagonal added in `main`.
fn element(i: usize) -> (Matrix3<f64>, Matrix3<f64>, Matrix3<f64>) {
    let s = 0.1 * (i as f64).sin();
    let aa = Matrix3::new(2.0, s, 0.0, s, 2.0, 0.1, 0.0, 0.1, 1.5);
    let ab = Matrix3::new(-1.0, 0.2, s, -0.2, -1.0, 0.1, s, -0.1, -0.5);
    (aa, ab, aa)
}

fn main() {
    println!("| graph | nodes | fill edges | tridiagonal factor / solve (us) | sparse factor / solve (us) | sparse / tridiagonal | ns / node | per node vs previous size |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|");
    for kind in ["chain", "twisted chain", "loop", "tree"] {
        let mut previous: Option<f64> = None;
        for n in [10, 100, 1000, 10000] {
            let (nodes, edges) = graph(kind, n);
            let pattern = Arc::new(if kind == "twisted chain" {
                BlockPattern::with_order(nodes, &edges, &BlockPattern::twisted_order(nodes))
            } else {
                BlockPattern::new(nodes, &edges)
            });
            let is_chain = kind.ends_with("chain");
            let mut assembled = SparseBlocks::new(pattern.clone());
            let mut tridiagonal = BlockTridiagonal::new(nodes);
            for (e, &(i, j)) in edges.iter().enumerate() {
                let (aa, ab, bb) = element(e);
                let slots = pattern.pair_slots(i, j).expect("an edge");
                assembled.add_pair_slots(slots, &aa, &ab, &bb, 1.0);
                if is_chain {
                    tridiagonal.add_pair(i, &[aa, ab, bb], 1.0);
                }
            }
            for dof in 0..3 * nodes {
                assembled.add_diagonal(dof, 1.0);
                tridiagonal.add_diagonal(dof, 1.0);
            }
            let rhs: Vec<f64> = (0..3 * nodes).map(|j| (0.7 * j as f64).cos()).collect();
            let (mut s, mut t) = (assembled.clone(), tridiagonal.clone());
            let (mut xs, mut xt) = (rhs.clone(), rhs.clone());
            let [sf, tf] = best_times(&mut [
                &mut || {
                    s.copy_from(&assembled);
                    s.factor_symmetric().expect("regular");
                },
                &mut || {
                    t.copy_from(&tridiagonal);
                    t.factor_symmetric().expect("regular");
                },
            ]);
            let [ss, ts] = best_times(&mut [
                &mut || {
                    xs.copy_from_slice(&rhs);
                    s.solve_in_place(black_box(&mut xs));
                },
                &mut || {
                    xt.copy_from_slice(&rhs);
                    t.solve_in_place(black_box(&mut xt));
                },
            ]);
            let sparse = sf + ss;
            let per_node = 1e9 * sparse / nodes as f64;
            let (tridiagonal_cell, ratio) = if is_chain {
                let tt = tf + ts;
                let cell = format!("{:.2} / {:.2}", 1e6 * tf, 1e6 * ts);
                (cell, format!("{:.2}", sparse / tt))
            } else {
                ("".to_string(), "".to_string())
            };
            println!(
                "| {kind} | {nodes} | {} | {tridiagonal_cell} | {:.2} / {:.2} | {ratio} | {per_node:.1} | {} |",
                pattern.fill_edges(),
                1e6 * sf,
                1e6 * ss,
                previous.map_or("".to_string(), |p| format!("{:.2}", per_node / p)),
            );
            previous = Some(per_node);
        }
    }
}
