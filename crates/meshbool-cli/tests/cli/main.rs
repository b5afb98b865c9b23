//! The `meshbool` binary end to end: outputs, exit codes and error messages, one file per
//! command (or family of commands) in one test binary; `rules` holds the rules every
//! command follows (exit codes, output paths, refusals that say where).

mod common;

mod boolean;
mod csg;
mod curves;
mod files;
mod make;
mod mining;
mod repair;
mod rules;
mod split;
