#pragma once
/// @file Internal to the language module: instructions that contradict themselves ("put the
/// marker in the holder and on the desk", "put the marker in the holder and keep it on the
/// desk") are refused, naming both requests, rather than planned as one of them.

#include <string>
#include <vector>

#include "lang2manip/symbolic/action.hpp"

namespace lang2manip::language_detail {

/// Throws PlanningError when two goals of one step, asked for together ("in the holder and on the
/// desk"), cannot hold together for the same object: in or on two different objects, in one
/// object and beside another, or opposite sides of the same one.
void refuseConflictingGoals(const std::vector<Goal>& stepGoals, const std::string& stepText);

/// Throws PlanningError when a goal moves an object the instruction says to keep where it is
/// (`kept`: a relation it keeps, or a zero displacement for "where it is").
void refuseMovingKeptObjects(const std::vector<Goal>& goals, const std::vector<Goal>& kept, const std::string& text);

}  // namespace lang2manip::language_detail
