//! The project as a whole: its layers, installers, README examples, Python
//! package and notebook pages.

mod installers;
mod layers;
mod notebook_pages;
mod python_package;
mod readme_examples;
