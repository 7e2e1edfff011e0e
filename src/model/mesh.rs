//! Where the nodes go: every station a scene names (supports, springs, point masses) is a node,
//! and the element count is spread over the segments between stations in proportion to their
//! lengths, at least one element each. When every station is a node of the uniform mesh, the
//! mesh is that uniform mesh, built as it always was (bit for bit).

/// Tolerance of "a station is a node of the uniform mesh of `n` elements", in elements: stations
/// written as decimals (1/3 as 0.3333333333333333) must count as nodes.
const ON_NODE: f64 = 1e-9;

/// Whether station `at` (a fraction of the length) is a node of `elements` equal elements.
pub fn on_uniform_node(at: f64, elements: usize) -> bool {
    let x = at * elements as f64;
    (x - x.round()).abs() <= ON_NODE * elements.max(1) as f64
}

/// The stations that must be nodes, sorted, without duplicates, with both ends added: the
/// segment boundaries of the mesh.
pub fn segment_boundaries(stations: impl IntoIterator<Item = f64>) -> Vec<f64> {
    let mut all: Vec<f64> = stations.into_iter().chain([0.0, 1.0]).collect();
    all.sort_by(f64::total_cmp);
    all.dedup_by(|b, a| (*b - *a).abs() <= 1e-12);
    all
}

/// The fewest elements that put every station on a node: one per segment.
pub fn fewest_elements(boundaries: &[f64]) -> usize {
    boundaries.len() - 1
}

/// The node positions (fractions of the length, from 0 to 1) of `elements` elements spread
/// over the segments between `boundaries`; `None` when every boundary is a node of the uniform
/// mesh of `elements` (then the caller builds that mesh). `elements` must be at least
/// [`fewest_elements`].
pub fn node_fractions(boundaries: &[f64], elements: usize) -> Option<Vec<f64>> {
    if boundaries.iter().all(|&b| on_uniform_node(b, elements)) {
        return None;
    }
    let counts = spread(boundaries, elements);
    let mut nodes = Vec::with_capacity(elements + 1);
    for (w, &count) in boundaries.windows(2).zip(&counts) {
        let (a, b) = (w[0], w[1]);
        nodes.extend((0..count).map(|k| a + (b - a) * k as f64 / count as f64));
    }
    nodes.push(1.0);
    Some(nodes)
}

/// Element counts per segment: proportional to the segment lengths (largest remainders), at
/// least one each, summing to `elements`.
fn spread(boundaries: &[f64], elements: usize) -> Vec<usize> {
    let ideal: Vec<f64> = boundaries
        .windows(2)
        .map(|w| (w[1] - w[0]) * elements as f64)
        .collect();
    assert!(
        elements >= ideal.len(),
        "{elements} elements for {} segments",
        ideal.len()
    );
    let mut counts: Vec<usize> = ideal.iter().map(|x| (x.floor() as usize).max(1)).collect();
    let shortfall = |counts: &[usize], j: usize| ideal[j] - counts[j] as f64;
    let mut total: usize = counts.iter().sum();
    while total < elements {
        let j = (0..counts.len())
            .max_by(|&a, &b| shortfall(&counts, a).total_cmp(&shortfall(&counts, b)))
            .expect("a segment");
        counts[j] += 1;
        total += 1;
    }
    while total > elements {
        let j = (0..counts.len())
            .filter(|&j| counts[j] > 1)
            .min_by(|&a, &b| shortfall(&counts, a).total_cmp(&shortfall(&counts, b)))
            .expect("more elements than segments");
        counts[j] -= 1;
        total -= 1;
    }
    counts
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stations_on_the_uniform_mesh_keep_it() {
        let b = segment_boundaries([1.0 / 3.0, 0.6666666666666666]);
        assert_eq!(fewest_elements(&b), 3);
        assert_eq!(node_fractions(&b, 30), None);
        assert!(node_fractions(&b, 10).is_some());
    }

    #[test]
    fn counts_follow_the_lengths_and_every_station_is_a_node() {
        let b = segment_boundaries([0.35, 0.0, 0.9]);
        assert_eq!(b, vec![0.0, 0.35, 0.9, 1.0]);
        // Shares 2.1 and 4.9: the larger remainder gets the element left over.
        assert_eq!(spread(&[0.0, 0.3, 1.0], 7), vec![2, 5]);
        assert_eq!(spread(&b, 3), vec![1, 1, 1]);
        assert_eq!(spread(&b, 4), vec![1, 2, 1]);
        for n in 3..200 {
            let counts = spread(&b, n);
            assert_eq!(counts.iter().sum::<usize>(), n);
            assert!(counts.iter().all(|&c| c >= 1));
            // Proportional: no segment more than one element off its share.
            for (c, w) in counts.iter().zip(b.windows(2)) {
                assert!(
                    (*c as f64 - (w[1] - w[0]) * n as f64).abs() < 1.0 + 1e-9,
                    "{n}"
                );
            }
            let nodes = node_fractions(&b, n)
                .unwrap_or_else(|| (0..=n).map(|i| i as f64 / n as f64).collect());
            assert_eq!(nodes.len(), n + 1);
            assert!(nodes.windows(2).all(|w| w[1] > w[0]));
            for s in &b {
                assert!(nodes.iter().any(|x| (x - s).abs() < 1e-12), "{n}: {s}");
            }
        }
    }
}
