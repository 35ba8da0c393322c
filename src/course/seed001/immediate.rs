//! `glBegin`/`glEnd` as the seed-001 course uses it: `glVertexAttrib*` changes the *current*
//! value of a generic attribute, and each `glVertex*` emits one vertex carrying the current
//! values of every attribute. The recorded vertices are then an ordinary vertex buffer.

/// A primitive being specified vertex by vertex.
#[derive(Clone, Debug)]
pub struct Immediate<V: Copy> {
    current: V,
    vertices: Vec<V>,
}

impl<V: Copy> Immediate<V> {
    /// `glBegin`, with GL's current attribute values (e.g. `glVertexAttrib` defaults
    /// (0, 0, 0, 1), `glColor` (1, 1, 1, 1)).
    pub fn begin(current: V) -> Self {
        Immediate {
            current,
            vertices: Vec::new(),
        }
    }

    /// `glVertexAttrib*`, `glColor*`, `glNormal*`: changes the current value only.
    pub fn attrib(&mut self, set: impl FnOnce(&mut V)) {
        set(&mut self.current);
    }

    /// `glVertex*`: sets the position and emits a vertex with the current attributes.
    pub fn vertex(&mut self, set: impl FnOnce(&mut V)) {
        set(&mut self.current);
        self.vertices.push(self.current);
    }

    /// `glEnd`: the vertices in the order they were emitted.
    pub fn end(self) -> Vec<V> {
        self.vertices
    }
}
