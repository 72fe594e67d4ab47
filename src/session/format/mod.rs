//! The session text format (version 1).
//!
//! ```text
//! # comment (to the end of the line)
//! drape 1                            # required first statement: format version
//! body builtin                       # or: body "path/to/body.obj" (relative to the session file)
//! units m                            # km | m | cm | mm: the units of the body file's coordinates
//! landmark waist y=0.98              # override a landmark's height (metres)
//! landmark front_neck at=0,1.31,0.08 # or its point
//!
//! mannequin layers=18 points=12 subdivisions=6   # steps, run in order
//! section y=0.60 name=mid_thigh
//! garment jumpsuit fit=tight resolution=6        # build a garment: jumpsuit | dress
//! set waist_girth +0.04                          # change a dimension: +d / -d relative, or a value
//! drag waist.front by=0,0,-0.03                  # drag a control point by a vector (m) ...
//! drag crotch.point to=0,0.70,0.07               # ... or to a position
//! drag left_knee by=0,0.02,0                     # drag a whole curve by a vector
//! undo                                           # back to the state before the last step
//! sculpt at=waist.front radius=0.08 peak=0.03    # push (peak < 0) or pull the surface there:
//!                                                # at= a control point or x,y,z; optional
//!                                                # dir=x,y,z falloff=biweight|wendland|smoothstep
//!                                                # eps=E (m) levels=N weight=W (Loop, 0..1)
//! ```
//!
//! The scene may also say how the constraint solver treats closed chains:
//! `solver chains=iterate passes=8` (the default) or `solver chains=split`.
//!
//! Scene statements (`drape`, `body`, `units`, `landmark`) come before the first step.
//! Arguments are `key=value`; unknown statements, keys or values are errors that name the
//! file, line and column. Everything is checked before anything runs.

//!
//! Four parts: [`statements`] (the table of every statement's keyword and place),
//! [`syntax`] (the typed session a parse produces), the lexer (a line into tokens) and the
//! parser (statements into the syntax tree, every name and value checked).

mod args;
mod lexer;
mod parser;
pub mod statements;
mod suggest;
pub mod syntax;

pub use parser::parse_session;
pub use statements::{Place, Statement};
pub use syntax::{Change, Layer, LogDetail, Op, ParseError, Scene, SculptAt, Session, Step, Units};
