//! A supernodal Cholesky solve on two cores by subtrees of the elimination tree.
//!
//! L y = b and Lᵀ x = y are solved supernode by supernode, as faer's supernodal solve
//! does: forward, each supernode's diagonal block solve then the update of the rows
//! of its pattern (its ancestors' columns); backward, the reverse. Two subtrees with
//! no ancestor in common touch disjoint rows, but for those of their common
//! ancestors. So the supernodes are split into two sides, each a union of whole
//! subtrees of about half the factor's terms, and the rest (the top: every ancestor
//! of both, with a nested-dissection ordering the last separators). Forward, each
//! side runs on its own core, its updates of the top's rows summed into a buffer of
//! its own, both buffers added to the top's rows after; then the top alone. Backward,
//! the top alone, then the two sides at once, each reading the top's finished rows.
//!
//! Each core streams its side's share of the factor once for all the columns, where
//! splitting the columns between the cores has each stream all of it. The factor's
//! reads bound the solve of a large factor, so the two-core solve of one column takes
//! about half the time of one core's. Every dense operation is faer's on the same
//! blocks in the same order as in its own solve; only the sums into the top's rows
//! are associated differently (the two sides' shares added last), so a result
//! differs from faer's in round-off there, and is the same on any machine.

use crate::numerics::{column, column_mut};
use faer::linalg::matmul::matmul;
use faer::linalg::triangular_solve::{solve_lower_triangular_in_place, solve_upper_triangular_in_place};
use faer::reborrow::{Reborrow, ReborrowMut};
use faer::sparse::linalg::cholesky::supernodal::{SupernodalLltRef, SymbolicSupernodalCholesky};
use faer::{Accum, MatMut, MatRef, Par};
use std::ops::Range;

/// The supernodes of a factor in the two sides and the top (each ascending: the
/// factor's order, children before their parents).
#[derive(Debug)]
pub struct Subtrees {
    sides: [Vec<usize>; 2],
    top: Vec<usize>,
    /// The rows (of the permuted matrix) of each side's supernodes' columns, as ranges.
    side_rows: [Vec<Range<usize>>; 2],
    /// The rows of the top's supernodes' columns, as ranges.
    top_rows: Vec<Range<usize>>,
    /// The longest pattern of a supernode (the rows of its update).
    widest: usize,
}

/// A side holds at most this share of the two sides' terms once split: past it a
/// heavier subtree is split into its children (whose root goes to the top).
const BALANCE: f64 = 0.55;

impl Subtrees {
    /// Splits the supernodes of `symbolic`: starting from the roots' subtrees, the
    /// heaviest subtree (by its terms) is replaced by its children, its root going to
    /// the top, until the subtrees dealt heaviest first to the lighter side leave
    /// neither side with more than [`BALANCE`] of their terms (or no subtree is left
    /// to split). None when the factor has a single chain of supernodes.
    pub fn new(symbolic: &SymbolicSupernodalCholesky<usize>) -> Option<Subtrees> {
        let ns = symbolic.n_supernodes();
        let begin = symbolic.supernode_begin();
        let end = symbolic.supernode_end();
        let mut supernode_of = vec![0; symbolic.nrows()];
        for s in 0..ns {
            supernode_of[begin[s]..end[s]].iter_mut().for_each(|x| *x = s);
        }
        // Each supernode's children, and its subtree's terms (its own and its
        // children's, which come before it: complete when it is reached).
        let (mut children, mut roots) = (vec![Vec::new(); ns], Vec::new());
        let (mut subtree, mut widest) = (vec![0usize; ns], 0);
        for s in 0..ns {
            let pattern = symbolic.supernode(s).pattern();
            let cols = end[s] - begin[s];
            subtree[s] += (cols + pattern.len()) * cols;
            widest = widest.max(pattern.len());
            match pattern.first() {
                Some(&row) => {
                    children[supernode_of[row]].push(s);
                    subtree[supernode_of[row]] += subtree[s];
                }
                None => roots.push(s),
            }
        }
        let mut candidates = roots;
        let deal = |candidates: &[usize]| {
            let mut order = candidates.to_vec();
            order.sort_by_key(|&s| std::cmp::Reverse((subtree[s], s)));
            let mut sides: [(usize, Vec<usize>); 2] = [(0, Vec::new()), (0, Vec::new())];
            for s in order {
                let lighter = if sides[0].0 <= sides[1].0 { 0 } else { 1 };
                sides[lighter].0 += subtree[s];
                sides[lighter].1.push(s);
            }
            sides
        };
        let sides = loop {
            let sides = deal(&candidates);
            let total = sides[0].0 + sides[1].0;
            let heaviest = candidates.iter().copied().max_by_key(|&s| (subtree[s], s));
            let balanced = sides[0].0.max(sides[1].0) as f64 <= BALANCE * total as f64;
            match heaviest {
                Some(h) if !balanced && !children[h].is_empty() => {
                    candidates.retain(|&s| s != h);
                    candidates.extend(&children[h]);
                }
                _ => break sides,
            }
        };
        if sides.iter().any(|(w, _)| *w == 0) {
            return None;
        }
        // Every supernode of each side's subtrees.
        let mut side_of = vec![usize::MAX; ns];
        for (k, (_, rs)) in sides.iter().enumerate() {
            for &r in rs {
                side_of[r] = k;
            }
        }
        for s in (0..ns).rev() {
            if side_of[s] != usize::MAX {
                for &c in &children[s] {
                    side_of[c] = side_of[s];
                }
            }
        }
        let (mut split, mut top) = ([Vec::new(), Vec::new()], Vec::new());
        for (s, &side) in side_of.iter().enumerate() {
            match side {
                usize::MAX => top.push(s),
                k => split[k].push(s),
            }
        }
        let rows = |set: &[usize]| merged(set.iter().map(|&s| begin[s]..end[s]));
        Some(Subtrees {
            side_rows: [rows(&split[0]), rows(&split[1])],
            top_rows: rows(&top),
            sides: split,
            top,
            widest,
        })
    }

    /// X ← L⁻ᵀL⁻¹X for X in the factor's own (permuted) order, the sides on two cores;
    /// `buffers` kept from one solve to the next.
    pub fn solve_in_place(&self, llt: SupernodalLltRef<'_, usize, f64>, mut x: MatMut<'_, f64>, buffers: &mut Buffers) {
        let (n, k) = (x.nrows(), x.ncols());
        let [a, b] = &mut buffers.sides;
        for y in [&mut *a, &mut *b] {
            y.resize(n * k, 0.0);
        }
        let mut works = std::mem::take(&mut buffers.works);
        for w in works.iter_mut() {
            w.resize(self.widest * k, 0.0);
        }
        let [work_a, work_b, work_top] = &mut works;
        // Forward: each side on its own copy, its own rows taken from X and the top's
        // starting at zero, so that they gather the side's share of the updates.
        let forward = |side: usize, y: &mut [f64], work: &mut [f64]| {
            let mut y = MatMut::from_column_major_slice_mut(y, n, k);
            copy_rows(&self.side_rows[side], x.rb(), y.rb_mut());
            for j in 0..k {
                let own = column_mut(y.rb_mut(), j);
                self.top_rows.iter().for_each(|r| own[r.clone()].fill(0.0));
            }
            for &s in &self.sides[side] {
                forward_supernode(llt, s, y.rb_mut(), work);
            }
        };
        crate::numerics::both(|| forward(0, a, work_a), || forward(1, b, work_b));
        let (ya, yb) = (
            MatMut::from_column_major_slice_mut(a, n, k),
            MatMut::from_column_major_slice_mut(b, n, k),
        );
        copy_rows(&self.side_rows[0], ya.rb(), x.rb_mut());
        copy_rows(&self.side_rows[1], yb.rb(), x.rb_mut());
        for j in 0..k {
            let (xj, aj, bj) = (column_mut(x.rb_mut(), j), column(ya.rb(), j), column(yb.rb(), j));
            for r in self.top_rows.iter().flat_map(|r| r.clone()) {
                xj[r] += aj[r] + bj[r];
            }
        }
        for &s in &self.top {
            forward_supernode(llt, s, x.rb_mut(), work_top);
        }
        for &s in self.top.iter().rev() {
            backward_supernode(llt, s, x.rb_mut(), work_top);
        }
        // Backward: each side on its copy, the top's rows now final.
        let backward = |side: usize, y: &mut [f64], work: &mut [f64]| {
            let mut y = MatMut::from_column_major_slice_mut(y, n, k);
            copy_rows(&self.top_rows, x.rb(), y.rb_mut());
            for &s in self.sides[side].iter().rev() {
                backward_supernode(llt, s, y.rb_mut(), work);
            }
        };
        crate::numerics::both(|| backward(0, a, work_a), || backward(1, b, work_b));
        copy_rows(&self.side_rows[0], MatRef::from_column_major_slice(a, n, k), x.rb_mut());
        copy_rows(&self.side_rows[1], MatRef::from_column_major_slice(b, n, k), x.rb_mut());
        buffers.works = works;
    }
}

/// The storage a split solve works in: each side's copy of X, and each core's
/// updates of a supernode's pattern.
#[derive(Debug, Default)]
pub struct Buffers {
    sides: [Vec<f64>; 2],
    works: [Vec<f64>; 3],
}

/// `to`'s rows in `rows` ← `from`'s, column by column.
fn copy_rows(rows: &[Range<usize>], from: MatRef<'_, f64>, mut to: MatMut<'_, f64>) {
    for j in 0..from.ncols() {
        let f = column(from, j);
        let t = column_mut(to.rb_mut(), j);
        for r in rows {
            t[r.clone()].copy_from_slice(&f[r.clone()]);
        }
    }
}

/// Consecutive ranges merged.
fn merged(ranges: impl Iterator<Item = Range<usize>>) -> Vec<Range<usize>> {
    let mut out: Vec<Range<usize>> = Vec::new();
    for r in ranges {
        match out.last_mut() {
            Some(last) if last.end == r.start => last.end = r.end,
            _ => out.push(r),
        }
    }
    out
}

/// Supernode s's forward step, as faer's: x_s ← L_ss⁻¹ x_s, then x_P −= L_Ps x_s for
/// the rows P of its pattern (`work` holds L_Ps x_s).
fn forward_supernode(llt: SupernodalLltRef<'_, usize, f64>, s: usize, mut x: MatMut<'_, f64>, work: &mut [f64]) {
    let node = llt.supernode(s);
    let l = node.val();
    let (size, pattern, k) = (l.ncols(), node.pattern(), x.ncols());
    let (top, bottom) = l.split_at_row(size);
    let mut xs = x.rb_mut().subrows_mut(node.start(), size);
    solve_lower_triangular_in_place(top, xs.rb_mut(), Par::Seq);
    let mut update = MatMut::from_column_major_slice_mut(&mut work[..pattern.len() * k], pattern.len(), k);
    matmul(update.rb_mut(), Accum::Replace, bottom, xs.rb(), 1.0, Par::Seq);
    for j in 0..k {
        let xj = column_mut(x.rb_mut(), j);
        let uj = column(update.rb(), j);
        for (&i, u) in pattern.iter().zip(uj) {
            xj[i] -= u;
        }
    }
}

/// Supernode s's backward step, as faer's: x_s −= L_Psᵀ x_P, then x_s ← L_ss⁻ᵀ x_s
/// (`work` holds x_P).
fn backward_supernode(llt: SupernodalLltRef<'_, usize, f64>, s: usize, mut x: MatMut<'_, f64>, work: &mut [f64]) {
    let node = llt.supernode(s);
    let l = node.val();
    let (size, pattern, k) = (l.ncols(), node.pattern(), x.ncols());
    let (top, bottom) = l.split_at_row(size);
    let mut gathered = MatMut::from_column_major_slice_mut(&mut work[..pattern.len() * k], pattern.len(), k);
    for j in 0..k {
        let xj = column(x.rb(), j);
        let gj = column_mut(gathered.rb_mut(), j);
        for (g, &i) in gj.iter_mut().zip(pattern) {
            *g = xj[i];
        }
    }
    let mut xs = x.rb_mut().subrows_mut(node.start(), size);
    matmul(
        xs.rb_mut(),
        Accum::Add,
        bottom.transpose(),
        gathered.rb(),
        -1.0,
        Par::Seq,
    );
    solve_upper_triangular_in_place(top.transpose(), xs.rb_mut(), Par::Seq);
}
