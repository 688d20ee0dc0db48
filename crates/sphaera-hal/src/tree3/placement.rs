//! Dividing a patch's faces among candidate triangles, and making the nodes that get a
//! region.

use std::collections::HashMap;

use super::{HalTree3, Node3};

impl HalTree3 {
    /// Divides `faces` among the candidate triangles (corners counter-clockwise, side
    /// ids): the faces are cut along the candidates' side paths, and each candidate gets
    /// the region to the left of its sides (the face holding the directed first edge of
    /// each of its sides' paths); a candidate whose sides disagree on that region, or
    /// whose region another took, approximates nothing and is discarded (the paper's
    /// coalescing paths). Returns the nodes made.
    pub(super) fn place(
        &mut self,
        faces: &[u32],
        candidates: &[([u32; 3], [u32; 3])],
        level: u32,
    ) -> Vec<u32> {
        let triangles = self.surface.mesh().triangles();
        let mut cut = std::collections::HashSet::new();
        for (_, sides) in candidates {
            for &side in sides {
                for pair in self.sides[side as usize].path.windows(2) {
                    cut.insert((pair[0].min(pair[1]), pair[0].max(pair[1])));
                }
            }
        }
        let (regions, region_of) = self.surface.regions(faces, &cut);
        let mut by_edge: HashMap<(u32, u32), Vec<u32>> = HashMap::new();
        let mut by_directed: HashMap<(u32, u32), u32> = HashMap::new();
        for &f in faces {
            let [a, b, c] = triangles[f as usize];
            for (u, v) in [(a, b), (b, c), (c, a)] {
                by_edge.entry((u.min(v), u.max(v))).or_default().push(f);
                by_directed.insert((u, v), f);
            }
        }
        // Every edge of a candidate's side paths votes for the region to its left (the
        // face holding the directed edge); each region goes to the candidate with the most
        // votes (the lowest on ties). Paths that coincide near a corner cast a few votes
        // on a neighbour's region; a candidate whose paths coalesce gets no region at all.
        let mut votes: HashMap<(u32, usize), usize> = HashMap::new();
        for (index, &(corners, sides)) in candidates.iter().enumerate() {
            for (k, &side) in sides.iter().enumerate() {
                let path = self.side_path(side, corners[k]);
                for edge in path.windows(2) {
                    if let Some(f) = by_directed.get(&(edge[0], edge[1])) {
                        *votes.entry((region_of[f], index)).or_default() += 1;
                    }
                }
            }
        }
        // First the candidates all of whose votes go to one region (their sides enclose
        // it: the rightful owner), the most votes first; then the regions left go to the
        // candidate with the most votes among those still without a region, then among all.
        let mut owner: Vec<Option<usize>> = vec![None; regions.len()];
        let mut voted: Vec<Vec<(u32, usize)>> = vec![Vec::new(); candidates.len()];
        let mut ballots: Vec<(&(u32, usize), &usize)> = votes.iter().collect();
        ballots.sort_by_key(|&(&(r, c), _)| (r, c));
        for &(&(r, c), &count) in &ballots {
            voted[c].push((r, count));
        }
        let mut sole: Vec<(usize, u32, usize)> = voted
            .iter()
            .enumerate()
            .filter(|(_, v)| v.len() == 1)
            .map(|(c, v)| (v[0].1, v[0].0, c))
            .collect();
        sole.sort_by(|x, y| y.0.cmp(&x.0).then(x.2.cmp(&y.2)));
        let mut owns = vec![false; candidates.len()];
        for (_, r, c) in sole {
            if owner[r as usize].is_none() {
                owner[r as usize] = Some(c);
                owns[c] = true;
            }
        }
        for pass in 0..2 {
            for (r, slot) in owner.iter_mut().enumerate() {
                if slot.is_some() {
                    continue;
                }
                let pick = ballots
                    .iter()
                    .filter(|&&(&(q, c), _)| q as usize == r && (pass == 1 || !owns[c]))
                    .max_by(|x, y| x.1.cmp(y.1).then(y.0.1.cmp(&x.0.1)))
                    .map(|&(&(_, c), _)| c);
                if let Some(c) = pick {
                    *slot = Some(c);
                    owns[c] = true;
                }
            }
        }
        if owner.iter().all(Option::is_none) {
            return Vec::new();
        }
        // Regions left between coinciding paths join the claimed neighbour they share the
        // most cut edges with (the lowest candidate on ties), until none is left.
        loop {
            let mut changed = false;
            for r in 0..regions.len() {
                if owner[r].is_some() {
                    continue;
                }
                let mut shared: HashMap<usize, usize> = HashMap::new();
                for &f in &regions[r] {
                    let [a, b, c] = triangles[f as usize];
                    for (u, v) in [(a, b), (b, c), (c, a)] {
                        for &g in &by_edge[&(u.min(v), u.max(v))] {
                            if let Some(o) = owner[region_of[&g] as usize] {
                                *shared.entry(o).or_default() += 1;
                            }
                        }
                    }
                }
                if let Some((&o, _)) = shared.iter().max_by(|x, y| x.1.cmp(y.1).then(y.0.cmp(x.0)))
                {
                    owner[r] = Some(o);
                    changed = true;
                }
            }
            if !changed {
                break;
            }
        }
        let mut made = Vec::new();
        for (index, &(corners, sides)) in candidates.iter().enumerate() {
            let mut patch: Vec<u32> = (0..regions.len())
                .filter(|&r| owner[r] == Some(index))
                .flat_map(|r| regions[r].iter().copied())
                .collect();
            if patch.is_empty() {
                continue;
            }
            patch.sort_unstable();
            made.push(self.make_node(corners, sides, patch, level));
        }
        made
    }

    /// A node for `corners` over `faces`: a leaf when the patch is the one face on these
    /// corners, else with its bounding volume.
    pub(super) fn make_node(
        &mut self,
        corners: [u32; 3],
        sides: [u32; 3],
        faces: Vec<u32>,
        level: u32,
    ) -> u32 {
        let positions = self.surface.mesh().positions();
        // A leaf is an original face on its own corners; a one-face patch on other corners
        // (paths that run out to a vertex and back) still splits at its face's third vertex.
        let leaf = faces.len() == 1 && {
            let mut face = self.surface.mesh().triangles()[faces[0] as usize];
            let mut own = corners;
            face.sort_unstable();
            own.sort_unstable();
            face == own
        };
        let (bound, width) = if leaf {
            (None, 0.0)
        } else {
            let bound = self.bound(corners, &faces);
            let points = corners.map(|v| positions[v as usize]);
            let (w1, w2) = bound.widths(points);
            (Some(bound), w1.max(w2))
        };
        self.nodes.push(Node3 {
            corners,
            level,
            faces,
            bound,
            width,
            children: Vec::new(),
            sides,
        });
        (self.nodes.len() - 1) as u32
    }
}
