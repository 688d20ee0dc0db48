//! A bounding-box hierarchy over the rings of a multipolygon, so that a query visits only
//! the rings whose boxes hold the point (a country's hundreds of islands cost a few box
//! tests, not one per island).

use glam::DVec2;

use crate::tree2::Box2;

/// Rings per leaf.
const LEAF: usize = 4;

/// One node: a box and either two children or a run of `order`.
#[derive(Clone, Debug)]
struct Node {
    bounds: Box2,
    /// `Ok((left, right))` children, or `Err((start, end))` a run of `order`.
    content: Result<(u32, u32), (u32, u32)>,
}

/// A box hierarchy over items (rings), built by median splits along the longer axis.
#[derive(Clone, Debug)]
pub(crate) struct RingIndex {
    nodes: Vec<Node>,
    order: Vec<u32>,
    boxes: Vec<Box2>,
}

impl RingIndex {
    /// The hierarchy over `boxes` (item `i` has box `boxes[i]`); deterministic.
    pub(crate) fn new(boxes: Vec<Box2>) -> Self {
        let mut index = Self {
            nodes: Vec::new(),
            order: (0..boxes.len() as u32).collect(),
            boxes,
        };
        if !index.order.is_empty() {
            index.grow(0, index.order.len());
        }
        index
    }

    /// Builds the node over `order[start..end]`, returning its id.
    fn grow(&mut self, start: usize, end: usize) -> u32 {
        let bounds = self.order[start..end]
            .iter()
            .fold(Box2::EMPTY, |b, &i| b.union(&self.boxes[i as usize]));
        let id = self.nodes.len() as u32;
        self.nodes.push(Node {
            bounds,
            content: Err((start as u32, end as u32)),
        });
        if end - start > LEAF {
            let extent = bounds.max - bounds.min;
            let axis = usize::from(extent.y > extent.x);
            let middle = start + (end - start) / 2;
            let boxes = &self.boxes;
            self.order[start..end].select_nth_unstable_by(middle - start, |&i, &j| {
                let center = |k: u32| boxes[k as usize].min[axis] + boxes[k as usize].max[axis];
                center(i).total_cmp(&center(j)).then(i.cmp(&j))
            });
            let left = self.grow(start, middle);
            let right = self.grow(middle, end);
            self.nodes[id as usize].content = Ok((left, right));
        }
        id
    }

    /// Calls `visit` with every item whose box holds `x`, in a fixed order.
    pub(crate) fn for_each_holding(&self, x: DVec2, visit: impl FnMut(usize)) {
        self.for_each_where(|b| b.holds(x), visit);
    }

    /// Calls `visit` with every item whose box meets `other`.
    pub(crate) fn for_each_meeting(&self, other: &Box2, visit: impl FnMut(usize)) {
        self.for_each_where(|b| !b.apart(other), visit);
    }

    /// Every item (in index order) whose box, and whose ancestors' boxes, pass `keep`.
    fn for_each_where(&self, keep: impl Fn(&Box2) -> bool, mut visit: impl FnMut(usize)) {
        if self.nodes.is_empty() {
            return;
        }
        let mut stack = vec![0_u32];
        while let Some(id) = stack.pop() {
            let node = &self.nodes[id as usize];
            if !keep(&node.bounds) {
                continue;
            }
            match node.content {
                Ok((left, right)) => {
                    stack.push(right);
                    stack.push(left);
                }
                Err((start, end)) => {
                    for &item in &self.order[start as usize..end as usize] {
                        if keep(&self.boxes[item as usize]) {
                            visit(item as usize);
                        }
                    }
                }
            }
        }
    }

    /// The items with their boxes' lower bound of the distance to `x`, nearest first.
    pub(crate) fn by_distance(&self, x: DVec2) -> Vec<(f64, usize)> {
        let mut items: Vec<(f64, usize)> = self
            .boxes
            .iter()
            .enumerate()
            .map(|(i, b)| (b.distance(x), i))
            .collect();
        items.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        items
    }
}
