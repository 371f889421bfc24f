//! Helpers shared by the scene tests.
#![allow(dead_code)]

pub mod builder;
pub mod corpus;
pub mod samples;
