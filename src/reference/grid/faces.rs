//! Which cells of each cube face a grid keeps lists for. Outside the
//! rectangle of cells that its triangles' spans meet, a face lists nothing,
//! and nothing is stored there; inside it, a grid asked to answer only the
//! rays towards a region (the image, for the eye's) builds the cells of
//! that region's rectangle alone, and the others defer to the BVH. So a
//! grid's arrays and its work follow the directions it serves, not the
//! whole sphere's 6 × 128² cells.

/// The cells [i0, i1] × [j0, j1] of one face.
pub(super) type Rect = [usize; 4];

/// Where a cell's list is, or what stands for it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Slot {
    /// Its index in the grid's lists.
    Listed(usize),
    /// No triangle is seen in it.
    Empty,
    /// Outside the region the grid answers for: ask the BVH.
    Unbuilt,
}

/// The face rectangles of a grid, and where its lists of each begin.
#[derive(Clone, Debug)]
pub(super) struct Faces {
    /// Per face, the cells some triangle's span meets.
    bounds: [Option<Rect>; 6],
    /// Per face, the cells whose lists are built (inside `bounds`) and the
    /// index of the first of them; row by row, face by face.
    built: [Option<(Rect, usize)>; 6],
    len: usize,
}

/// The smallest rectangle holding both.
pub(super) fn union(a: Option<Rect>, [i0, i1, j0, j1]: Rect) -> Rect {
    match a {
        None => [i0, i1, j0, j1],
        Some([a0, a1, b0, b1]) => [a0.min(i0), a1.max(i1), b0.min(j0), b1.max(j1)],
    }
}

fn intersection([a0, a1, b0, b1]: Rect, [i0, i1, j0, j1]: Rect) -> Option<Rect> {
    let r = [a0.max(i0), a1.min(i1), b0.max(j0), b1.min(j1)];
    (r[0] <= r[1] && r[2] <= r[3]).then_some(r)
}

fn width([i0, i1, _, _]: &Rect) -> usize {
    i1 - i0 + 1
}

fn area(r: &Rect) -> usize {
    width(r) * (r[3] - r[2] + 1)
}

/// The index of cell (i, j)'s list in a built rectangle whose first list
/// is `first` (row by row).
fn list_of((rect, first): (Rect, usize), i: usize, j: usize) -> usize {
    first + (j - rect[2]) * width(&rect) + i - rect[0]
}

impl Faces {
    /// The rectangles of the spans (face, cells), the built ones cut to
    /// `region`'s where there is one (per face; None: nothing there).
    pub(super) fn new(
        spans: impl IntoIterator<Item = (usize, Rect)>,
        region: Option<&[Option<Rect>; 6]>,
    ) -> Self {
        let mut bounds = [None; 6];
        for (face, rect) in spans {
            bounds[face] = Some(union(bounds[face], rect));
        }
        let mut built = [None; 6];
        let mut len = 0;
        for face in 0..6 {
            let cut = match (bounds[face], region) {
                (Some(rect), Some(region)) => region[face].and_then(|r| intersection(rect, r)),
                (rect, _) => rect,
            };
            if let Some(rect) = cut {
                built[face] = Some((rect, len));
                len += area(&rect);
            }
        }
        Self { bounds, built, len }
    }

    /// How many lists are built.
    pub(super) fn len(&self) -> usize {
        self.len
    }

    /// Where the list of cell (i, j) of `face` is.
    #[inline]
    pub(super) fn slot(&self, face: usize, i: usize, j: usize) -> Slot {
        let inside = |&[i0, i1, j0, j1]: &Rect| (i0..=i1).contains(&i) && (j0..=j1).contains(&j);
        match self.built[face] {
            Some(built) if inside(&built.0) => Slot::Listed(list_of(built, i, j)),
            _ if self.bounds[face].as_ref().is_some_and(inside) => Slot::Unbuilt,
            _ => Slot::Empty,
        }
    }

    /// The built lists among the cells `rect` of `face`.
    pub(super) fn lists_in(&self, face: usize, rect: Rect) -> impl Iterator<Item = usize> {
        let cut = self.built[face].and_then(|built| Some((intersection(built.0, rect)?, built)));
        cut.into_iter().flat_map(|([i0, i1, j0, j1], built)| {
            (j0..=j1).flat_map(move |j| (i0..=i1).map(move |i| list_of(built, i, j)))
        })
    }

    /// Each built list's face and cell (i, j), in the lists' order.
    pub(super) fn cells(&self) -> impl Iterator<Item = (usize, usize, usize)> + '_ {
        self.built.iter().enumerate().flat_map(|(face, built)| {
            built.iter().flat_map(move |&([i0, i1, j0, j1], _)| {
                (j0..=j1).flat_map(move |j| (i0..=i1).map(move |i| (face, i, j)))
            })
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two spans on face 0, one on face 3, and a region that cuts face 0 and
    /// leaves out face 3: every cell's slot, against the rectangles by hand,
    /// and the built lists numbered in the order `cells` gives.
    #[test]
    fn slots_follow_the_spans_and_the_region() {
        let spans = [(0, [2, 4, 10, 12]), (0, [8, 9, 1, 3]), (3, [0, 5, 0, 5])];
        let mut region = [None; 6];
        region[0] = Some([3, 20, 0, 11]);
        let faces = Faces::new(spans, Some(&region));
        // Face 0's bounds [2, 9] × [1, 12], cut to [3, 9] × [1, 11].
        assert_eq!(faces.len(), 7 * 11);
        let listed: Vec<_> = faces.cells().collect();
        assert_eq!(listed.len(), faces.len());
        for (k, &(face, i, j)) in listed.iter().enumerate() {
            assert_eq!(faces.slot(face, i, j), Slot::Listed(k));
        }
        assert_eq!(faces.slot(0, 2, 5), Slot::Unbuilt);
        assert_eq!(faces.slot(0, 5, 12), Slot::Unbuilt);
        assert_eq!(faces.slot(0, 10, 5), Slot::Empty);
        assert_eq!(faces.slot(0, 5, 0), Slot::Empty);
        assert_eq!(faces.slot(3, 1, 1), Slot::Unbuilt);
        assert_eq!(faces.slot(1, 1, 1), Slot::Empty);
        let in_span: Vec<_> = faces.lists_in(0, [2, 4, 10, 12]).collect();
        let expected: Vec<_> = listed
            .iter()
            .enumerate()
            .filter(|&(_, &(_, i, j))| (2..=4).contains(&i) && (10..=12).contains(&j))
            .map(|(k, _)| k)
            .collect();
        assert_eq!(in_span, expected);
        // Without a region every spanned cell is built.
        let all = Faces::new(spans, None);
        assert_eq!(all.len(), 8 * 12 + 36);
        assert_eq!(all.slot(0, 2, 5), Slot::Listed(4 * 8));
        assert_eq!(all.slot(3, 1, 1), Slot::Listed(8 * 12 + 7));
    }
}
