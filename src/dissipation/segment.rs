//! The four segments of the steady cycle, in the order θ increases: E → B (reverse
//! slip), B → C (full stick), C → H (forward slip by the mirror point Y), H → E
//! (forward slip by P_K).

use std::fmt;

use crate::real::Real;

/// One of the four segments of the cycle (paper Section 3.4).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Segment {
    /// E → B: reverse slip spreading inward.
    EB,
    /// B → C: the whole contact sticks.
    BC,
    /// C → H: forward slip, governed by the mirror point Y.
    CH,
    /// H → E: forward slip, governed by P_K.
    HE,
}

impl Segment {
    /// The segments in cycle order.
    pub const ALL: [Segment; 4] = [Segment::EB, Segment::BC, Segment::CH, Segment::HE];

    /// "EB", "BC", "CH" or "HE".
    pub fn name(self) -> &'static str {
        match self {
            Segment::EB => "EB",
            Segment::BC => "BC",
            Segment::CH => "CH",
            Segment::HE => "HE",
        }
    }
}

impl fmt::Display for Segment {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The four segment contributions to W, each ∫ (Q − Q0) du over the segment.
#[derive(Clone, Debug, PartialEq)]
pub struct Segments<R> {
    /// E → B: reverse slip spreading inward.
    pub eb: R,
    /// B → C: the whole contact sticks.
    pub bc: R,
    /// C → H: forward slip, governed by the mirror point Y.
    pub ch: R,
    /// H → E: forward slip, governed by P_K.
    pub he: R,
}

impl<R> Segments<R> {
    /// Each segment's value from `value`, in cycle order.
    pub fn from_fn(mut value: impl FnMut(Segment) -> R) -> Self {
        Segments {
            eb: value(Segment::EB),
            bc: value(Segment::BC),
            ch: value(Segment::CH),
            he: value(Segment::HE),
        }
    }

    /// The value of `segment`.
    pub fn get(&self, segment: Segment) -> &R {
        match segment {
            Segment::EB => &self.eb,
            Segment::BC => &self.bc,
            Segment::CH => &self.ch,
            Segment::HE => &self.he,
        }
    }

    /// The value of `segment`, to change.
    pub fn get_mut(&mut self, segment: Segment) -> &mut R {
        match segment {
            Segment::EB => &mut self.eb,
            Segment::BC => &mut self.bc,
            Segment::CH => &mut self.ch,
            Segment::HE => &mut self.he,
        }
    }

    /// The segments with their values, in cycle order.
    pub fn iter(&self) -> impl Iterator<Item = (Segment, &R)> {
        Segment::ALL
            .into_iter()
            .map(move |segment| (segment, self.get(segment)))
    }

    /// The segments as (name, value) pairs, in cycle order.
    pub fn named(&self) -> [(&'static str, &R); 4] {
        Segment::ALL.map(|segment| (segment.name(), self.get(segment)))
    }
}

impl<R: Real> Segments<R> {
    /// EB + BC + CH + HE.
    pub fn total(&self) -> R {
        self.eb.clone() + &self.bc + &self.ch + &self.he
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segments_are_named_and_visited_in_cycle_order() {
        let names: Vec<String> = Segment::ALL.iter().map(|segment| segment.to_string()).collect();
        assert_eq!(names, ["EB", "BC", "CH", "HE"]);
        let mut values = Segments::from_fn(|segment| segment as usize as f64);
        *values.get_mut(Segment::CH) += 10.0;
        assert_eq!(*values.get(Segment::CH), 12.0);
        let visited: Vec<(Segment, f64)> = values.iter().map(|(segment, value)| (segment, *value)).collect();
        assert_eq!(
            visited,
            [
                (Segment::EB, 0.0),
                (Segment::BC, 1.0),
                (Segment::CH, 12.0),
                (Segment::HE, 3.0)
            ]
        );
        assert_eq!(values.named()[3], ("HE", &3.0));
        assert_eq!(values.total(), 16.0);
    }
}
