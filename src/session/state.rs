//! What a session carries from step to step: the body with its index, the current garment
//! and the undo history of its edits.

use crate::body::Body;
use crate::collision::DetectState;
use crate::constraint::{ConstraintNet, Edit};
use crate::garment::{BodyProbe, Dimensions, Framework, FrameworkOptions, TemplateKind};

use super::stage::{CollisionOutcome, M1Outcome, SculptOutcome};
use crate::collision::GarmentMesh;
use crate::import::ImportedGarment;
use crate::m1::StoredCut;
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

use super::error::StepError;

/// A garment from a file (`garment mesh`): the file as read and prepared for the
/// collision, its face regions (the patches M1's selection rules judge), its name and ease.
pub(crate) struct FileGarment {
    /// The name files and the log give it.
    pub(crate) name: String,
    /// The file, welded and oriented, its faces' patches the regions below.
    pub(crate) imported: Arc<ImportedGarment>,
    /// The face regions' names (`GROUP/LETTER`: the file's group and the body partition).
    pub(crate) regions: Vec<String>,
    /// The gap a moved vertex stands off the skin, m.
    pub(crate) ease: f64,
}

/// The state between steps.
pub(crate) struct SessionState {
    /// The scene's body.
    pub(crate) body: Body,
    /// The body's one index (curve clearance and collision), built by the first garment.
    pub(crate) probe: Option<BodyProbe>,
    /// The garment the running step works on (taken from [`Self::worn`] for the step and
    /// put back after it).
    pub(crate) garment: Option<GarmentState>,
    /// That garment's states before each of its drags, sets, cuts and sculpts, for `undo`.
    pub(crate) history: History,
    /// The garments worn, innermost first, each with its undo history.
    pub(crate) worn: Vec<Worn>,
    /// Per step `undo` can take back, the garments it changed (indices into
    /// [`Self::worn`]): the edited one, then those over it that it pushed.
    pub(crate) undo: Vec<Vec<usize>>,
    /// The limit [`Self::undo`] was cut to when its oldest steps were dropped.
    pub(crate) undo_dropped_past: Option<usize>,
    /// NURBS parts, in the order added (none: no NURBS work at all).
    pub(crate) nurbs: Vec<crate::nurbs::NurbsPart>,
    /// The body's triangle hulls for the NURBS parts, built with the first part.
    pub(crate) nurbs_body: Option<crate::nurbs::BodyHulls>,
}

impl SessionState {
    /// The state after the scene: a body, no garment yet.
    pub(crate) fn new(body: Body) -> Self {
        Self {
            body,
            probe: None,
            garment: None,
            history: History::default(),
            worn: Vec::new(),
            undo: Vec::new(),
            undo_dropped_past: None,
            nurbs: Vec::new(),
            nurbs_body: None,
        }
    }

    /// Keeps the last `limit` edits for `undo` (of the garment, of each garment worn, and of
    /// the steps over worn garments), dropping the oldest states past them. A worn
    /// garment's states are those before the steps that changed it, the newest last, so the
    /// last `limit` steps find theirs.
    pub(crate) fn keep_last(&mut self, limit: usize) {
        self.history.keep_last(limit);
        for w in &mut self.worn {
            w.history.keep_last(limit);
        }
        if self.undo.len() > limit {
            self.undo.drain(..self.undo.len() - limit);
            self.undo_dropped_past = Some(limit);
        }
    }

    /// Makes `next` the current garment; the one it replaces can be restored by `undo`.
    pub(crate) fn advance(&mut self, next: GarmentState) {
        if let Some(previous) = self.garment.replace(next) {
            self.history.push(previous);
        }
    }
}

/// A garment's undo history: its states before each undoable step, the newest last. A state
/// goes in without M1's caches, which only the step after it reads (each state kept its
/// own, some 12 MB a drag at resolution 24, all in new pages), and without M1 itself where
/// M1 can be made again from what the state keeps ([`GarmentState::for_history`]: about
/// half of what a state holds, some 7.7 MB left a drag at resolution 24). A state restored
/// from it (by `undo`, or by a refused edit of a garment worn under others) takes the caches
/// of the state it replaces and makes its M1 again from them, the same bit for bit
/// (`flow::restore::restore_m1`).
#[derive(Default)]
pub(crate) struct History {
    states: Vec<GarmentState>,
    /// The limit it was cut to when its oldest states were dropped ([`Self::keep_last`]).
    dropped_past: Option<usize>,
}

impl History {
    /// Keeps `state` (without M1's caches, and without M1 where it can be made again) as
    /// the one `undo` restores next.
    pub(crate) fn push(&mut self, state: GarmentState) {
        self.states.push(state.for_history());
    }

    /// The state `undo` restores next, taken out; when there is none, why.
    pub(crate) fn pop(&mut self) -> Result<GarmentState, StepError> {
        self.states.pop().ok_or(match self.dropped_past {
            Some(limit) => StepError::UndoLimit(limit),
            None => StepError::NothingToUndo,
        })
    }

    /// The state `undo` would restore next.
    pub(crate) fn last(&self) -> Option<&GarmentState> {
        self.states.last()
    }

    /// How many states it holds.
    pub(crate) fn len(&self) -> usize {
        self.states.len()
    }

    /// Forgets every state (a new garment).
    pub(crate) fn clear(&mut self) {
        self.states.clear();
        self.dropped_past = None;
    }

    /// Drops the oldest states past the last `limit`.
    pub(crate) fn keep_last(&mut self, limit: usize) {
        if self.states.len() > limit {
            self.states.drain(..self.states.len() - limit);
            self.dropped_past = Some(limit);
        }
    }
}

/// A garment the session wears, with its undo history.
pub(crate) struct Worn {
    /// Its name (what edits name it by).
    pub(crate) name: String,
    /// Its state (`None` only while a step works on it, in [`SessionState::garment`]).
    pub(crate) garment: Option<GarmentState>,
    /// Its states before each of its undoable steps.
    pub(crate) history: History,
}

/// The current garment: its template, settings, the dimensions set so far, the solve, the
/// drags made since, its constraint network, and what collision remembers between steps.
#[derive(Clone)]
pub(crate) struct GarmentState {
    /// Template (`None`: a garment from a file, [`Self::file`]).
    pub(crate) template: Option<TemplateKind>,
    /// The name it was given (`garment dress name=outer`), when not its template's.
    pub(crate) label: Option<String>,
    /// The garment read from a file by `garment mesh` (`None`: built from its template).
    pub(crate) file: Option<Arc<FileGarment>>,
    /// Framework settings (fit, resolution).
    pub(crate) options: FrameworkOptions,
    /// Dimensions the session set.
    pub(crate) dims: Dimensions,
    /// The solved framework and M0 (before collision response).
    pub(crate) framework: Option<Framework>,
    /// What detection remembers between steps (inert points, patch skipping, the distances
    /// measured): one memory shared by this garment's states, the current one and those in
    /// its history, so that no step copies it. Each answer in it is kept with the position
    /// it was found at and read only at that position (the topology too), so a state that
    /// `undo` restores reads it as well as the state that wrote it: what stands elsewhere
    /// is measured again.
    pub(crate) detect: Arc<Mutex<DetectState>>,
    /// The last collision of M0.
    pub(crate) collision: Option<CollisionOutcome>,
    /// The constraint network.
    pub(crate) net: Option<ConstraintNet>,
    /// Drags made since the last dimension change, replayed after the next one.
    pub(crate) edits: Vec<Edit>,
    /// M0's positions as the garment was first built (the standard size M1's stretch rule
    /// compares with; the topology never changes).
    pub(crate) standard: Option<Arc<Vec<glam::DVec3>>>,
    /// The last M1, when the scene asks for one.
    pub(crate) m1: Option<M1Outcome>,
    /// M1 was left out of this state as [`History`] keeps it ([`Self::for_history`]): it is
    /// made again when the state is restored.
    pub(crate) m1_left_out: bool,
    /// What the last M1's collision leaves for the next, patch by patch: kept through
    /// edits (a patch whose input is unchanged takes its collision from here).
    pub(crate) m1_reuse: Option<Arc<crate::m1::M1Reuse>>,
    /// The last M1's shape: kept through edits (an M1 over an M0 of the same faces, patches
    /// and refinement only places its vertices again).
    pub(crate) m1_shape: Option<Arc<crate::m1::M1Shape>>,
    /// What M1's selection last read and found, patch by patch, with M0's edges and their
    /// faces: kept through edits.
    pub(crate) m0_select: Option<Arc<crate::m1::SelectMemory>>,
    /// The last pattern, when the scene asks for one (or why it could not be made).
    pub(crate) patterns: Option<Result<crate::pattern::Pattern, crate::pattern::PatternError>>,
    /// The cut lines, stored on M0.
    pub(crate) cuts: Vec<StoredCut>,
    /// The cut lines through picked points: their names and M0 vertices.
    pub(crate) through_cuts: Vec<(String, Vec<u32>)>,
    /// The sculpts made, in order: made again on the new mesh after every rebuild.
    pub(crate) sculpts: Vec<(super::SculptAt, crate::sculpt::Drag, crate::sculpt::SculptOptions)>,
    /// The last sculpt's result (the garment's latest mesh), when there are sculpts.
    pub(crate) sculpted: Option<SculptOutcome>,
    /// When it is worn over other garments: how it was pushed out in front of them.
    pub(crate) layered: Option<super::stage::Layered>,
}

impl GarmentState {
    /// A garment from a file: its M0 is the file's mesh, never solved again.
    pub(crate) fn from_file(file: FileGarment) -> Self {
        Self {
            template: None,
            file: Some(Arc::new(file)),
            ..Self::new(TemplateKind::Jumpsuit, FrameworkOptions::default())
        }
    }

    /// The garment's name: its template's, or the file garment's.
    pub(crate) fn name(&self) -> String {
        match (&self.file, self.template) {
            (Some(f), _) => f.name.clone(),
            (None, _) if self.label.is_some() => self.label.clone().unwrap_or_default(),
            (None, Some(t)) => t.name().to_string(),
            (None, None) => "garment".into(),
        }
    }

    /// The gap the collision stands M0 off the skin, m: the framework's, or the file
    /// garment's (`None` before a template garment is solved).
    pub(crate) fn ease(&self) -> Option<f64> {
        match (&self.framework, &self.file) {
            (Some(fw), _) => Some(fw.ease()),
            (None, Some(f)) => Some(f.ease),
            (None, None) => None,
        }
    }

    /// M0 as the collision layers see it, with its roles (`None` before a template garment
    /// is solved).
    pub(crate) fn collision_mesh(&self, body_height: f64) -> Option<GarmentMesh> {
        match (&self.framework, &self.file) {
            (Some(fw), _) => Some(GarmentMesh::from_framework(fw, body_height)),
            (None, Some(f)) => Some(f.imported.mesh.clone()),
            (None, None) => None,
        }
    }

    /// How many patches M0 has (a file garment's face regions).
    pub(crate) fn patch_count(&self) -> usize {
        match (&self.framework, &self.file) {
            (Some(fw), _) => fw.m0.patch_names.len(),
            (None, Some(f)) => f.regions.len(),
            (None, None) => 0,
        }
    }

    /// Detection's memory (see [`Self::detect`]), for one collision or one update.
    pub(crate) fn detect_memory(&self) -> MutexGuard<'_, DetectState> {
        self.detect.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// The state as [`History`] keeps it: without M1's caches (its patches' collisions,
    /// its shape and its selection's memory), and without M1 when M1 is made from what the
    /// state keeps alone (its collided M0, its cut lines and its standard size): no sculpt
    /// was made on it and it was not pushed out in front of another garment.
    fn for_history(mut self) -> Self {
        self.m1_reuse = None;
        self.m1_shape = None;
        self.m0_select = None;
        if self.m1.is_some() && self.sculpts.is_empty() && self.sculpted.is_none() && self.layered.is_none() {
            self.m1 = None;
            self.m1_left_out = true;
        }
        self
    }

    /// Takes M1's caches from `later` (the state `undo` drops). A cache answers only for the
    /// same inputs (a patch's M0 and selection, M0's faces, patches and refinement), which it
    /// checks, so an earlier state reads it as safely as the state that made it: M1 is the
    /// same, bit for bit, as one built whole.
    pub(crate) fn take_caches(&mut self, later: &mut Self) {
        self.m1_reuse = later.m1_reuse.take();
        self.m1_shape = later.m1_shape.take();
        self.m0_select = later.m0_select.take();
    }

    /// A new garment, not yet solved.
    pub(crate) fn new(template: TemplateKind, options: FrameworkOptions) -> Self {
        Self {
            template: Some(template),
            label: None,
            file: None,
            options,
            dims: Dimensions::default(),
            framework: None,
            detect: Arc::default(),
            collision: None,
            net: None,
            edits: Vec::new(),
            standard: None,
            m1: None,
            m1_left_out: false,
            m1_reuse: None,
            m1_shape: None,
            m0_select: None,
            patterns: None,
            cuts: Vec::new(),
            through_cuts: Vec::new(),
            sculpts: Vec::new(),
            sculpted: None,
            layered: None,
        }
    }

    /// The same garment with its dimensions, detection memory and drags, to be solved again
    /// (its framework, collision and network cleared; its pattern kept, for the panels the
    /// next one does not change).
    pub(crate) fn unsolved(&self) -> Self {
        Self {
            template: self.template,
            label: self.label.clone(),
            file: self.file.clone(),
            options: self.options,
            dims: self.dims.clone(),
            framework: None,
            detect: Arc::clone(&self.detect),
            collision: None,
            net: None,
            edits: self.edits.clone(),
            standard: self.standard.clone(),
            m1: None,
            m1_left_out: false,
            m1_reuse: self.m1_reuse.clone(),
            m1_shape: self.m1_shape.clone(),
            m0_select: self.m0_select.clone(),
            patterns: self.patterns.clone(),
            cuts: self.cuts.clone(),
            through_cuts: self.through_cuts.clone(),
            sculpts: self.sculpts.clone(),
            sculpted: None,
            layered: None,
        }
    }

    /// The same garment on the new `framework`, not yet collided: everything else kept. The
    /// old framework and collision are not copied, nor M1 and the sculpted mesh, which the
    /// collision makes again. (Copying M1 made its timed stages look faster, as the next
    /// M1 then reused the pages the dropped copy freed, but the session slower: the demo at
    /// resolution 24, one core, ran 1,978 ms with the copy and 1,931 without.)
    pub(crate) fn on_framework(&self, framework: Framework) -> Self {
        Self {
            framework: Some(framework),
            net: self.net.clone(),
            ..self.unsolved()
        }
    }
}
