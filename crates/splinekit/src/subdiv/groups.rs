//! An indexed parallel iterator over values made a fixed number `K` at a time, so that a
//! pass can share the loads of one stencil among the `K` values it gives and still collect
//! straight into the output (`collect_into_vec`), without an initialized buffer to fill.

use rayon::iter::plumbing::{Consumer, Folder, Producer, ProducerCallback, UnindexedConsumer, bridge};
use rayon::prelude::*;

/// The `K · n` values `make(0)[0], make(0)[1], …, make(n − 1)[K − 1]`.
pub(crate) fn groups<T, F, const K: usize>(n: usize, make: F) -> Groups<F, K>
where
    T: Copy + Default + Send,
    F: Fn(u32) -> [T; K] + Sync + Send,
{
    Groups { len: K * n, make }
}

/// See [`groups`].
#[derive(Clone)]
pub(crate) struct Groups<F, const K: usize> {
    len: usize,
    make: F,
}

impl<T, F, const K: usize> ParallelIterator for Groups<F, K>
where
    T: Copy + Default + Send,
    F: Fn(u32) -> [T; K] + Sync + Send,
{
    type Item = T;

    fn drive_unindexed<C: UnindexedConsumer<T>>(self, consumer: C) -> C::Result {
        bridge(self, consumer)
    }

    fn opt_len(&self) -> Option<usize> {
        Some(self.len)
    }
}

impl<T, F, const K: usize> IndexedParallelIterator for Groups<F, K>
where
    T: Copy + Default + Send,
    F: Fn(u32) -> [T; K] + Sync + Send,
{
    fn len(&self) -> usize {
        self.len
    }

    fn drive<C: Consumer<T>>(self, consumer: C) -> C::Result {
        bridge(self, consumer)
    }

    fn with_producer<CB: ProducerCallback<T>>(self, callback: CB) -> CB::Output {
        callback.callback(GroupsProducer::<F, K> { make: &self.make, start: 0, end: self.len })
    }
}

/// The values `start .. end` of a [`Groups`].
struct GroupsProducer<'a, F, const K: usize> {
    make: &'a F,
    start: usize,
    end: usize,
}

impl<'a, T, F, const K: usize> Producer for GroupsProducer<'a, F, K>
where
    T: Copy + Default + Send,
    F: Fn(u32) -> [T; K] + Sync + Send,
{
    type Item = T;
    type IntoIter = GroupsIter<'a, F, T, K>;

    fn into_iter(self) -> Self::IntoIter {
        GroupsIter {
            make: self.make,
            group: (self.start / K) as u32,
            k: self.start % K,
            values: [T::default(); K],
            fresh: false,
            front: self.start,
            back: self.end,
        }
    }

    fn fold_with<G: Folder<T>>(self, mut folder: G) -> G {
        let mut i = self.start;
        while i < self.end {
            let g = i / K;
            let values = (self.make)(g as u32);
            let hi = self.end.min((g + 1) * K);
            for &v in &values[i - g * K..hi - g * K] {
                folder = folder.consume(v);
            }
            if folder.full() {
                break;
            }
            i = hi;
        }
        folder
    }

    fn split_at(self, index: usize) -> (Self, Self) {
        let mid = self.start + index;
        (Self { end: mid, ..self }, Self { start: mid, ..self })
    }
}

impl<F, const K: usize> Clone for GroupsProducer<'_, F, K> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<F, const K: usize> Copy for GroupsProducer<'_, F, K> {}

/// The sequential iterator of a [`GroupsProducer`]: keeps the values of the group it is in.
pub(crate) struct GroupsIter<'a, F, T, const K: usize> {
    make: &'a F,
    /// The group of `front`, and `front`'s place in it.
    group: u32,
    k: usize,
    /// `make(group)`, when `fresh`.
    values: [T; K],
    fresh: bool,
    front: usize,
    back: usize,
}

impl<T, F, const K: usize> Iterator for GroupsIter<'_, F, T, K>
where
    T: Copy,
    F: Fn(u32) -> [T; K],
{
    type Item = T;

    #[inline]
    fn next(&mut self) -> Option<T> {
        if self.front == self.back {
            return None;
        }
        if !self.fresh {
            self.values = (self.make)(self.group);
            self.fresh = true;
        }
        let v = self.values[self.k];
        self.front += 1;
        self.k += 1;
        if self.k == K {
            self.k = 0;
            self.group += 1;
            self.fresh = false;
        }
        Some(v)
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = self.back - self.front;
        (n, Some(n))
    }
}

impl<T, F, const K: usize> DoubleEndedIterator for GroupsIter<'_, F, T, K>
where
    T: Copy,
    F: Fn(u32) -> [T; K],
{
    /// Not used by rayon's collection: makes the last group again for every value.
    fn next_back(&mut self) -> Option<T> {
        if self.front == self.back {
            return None;
        }
        self.back -= 1;
        Some((self.make)((self.back / K) as u32)[self.back % K])
    }
}

impl<T, F, const K: usize> ExactSizeIterator for GroupsIter<'_, F, T, K>
where
    T: Copy,
    F: Fn(u32) -> [T; K],
{
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn groups_are_flattened_in_order() {
        let make = |g: u32| [3 * g, 3 * g + 1, 3 * g + 2];
        let mut out = Vec::new();
        groups(1000, make).with_min_len(7).collect_into_vec(&mut out);
        assert_eq!(out, (0..3000).collect::<Vec<u32>>());
        let back: Vec<u32> = GroupsProducer::<_, 3> { make: &make, start: 4, end: 11 }.into_iter().rev().collect();
        assert_eq!(back, (4..11).rev().collect::<Vec<u32>>());
        let (a, b) = GroupsProducer::<_, 3> { make: &make, start: 2, end: 20 }.split_at(5);
        let joined: Vec<u32> = a.into_iter().chain(b.into_iter()).collect();
        assert_eq!(joined, (2..20).collect::<Vec<u32>>());
    }
}
