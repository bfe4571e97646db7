#pragma once
/** @file linked_merge.h
 * (Internal to dynslam::ekf.) The linked-merge module (classify_merge_linked with an
 * object-centric model, doc/results/classification.md "Merging a linked object"). AfterCommit:
 * the router's merges of the step (TRoutedStep::merges) by the state surgery mergeObjects
 * (state_surgery.h), counted in the report. Enabled with a router the options make when it may
 * merge, and with every router set by setRouter (whose merges the options do not tell). */
#include <memory>

#include "filter_module.h"

namespace dynslam::ekf
{
class CLinkedMergeModule : public IFilterModule
{
public:
	std::string name() const override { return "linked_merge"; }
	unsigned hooks() const override { return hookBit(Hook::AfterCommit); }
	void afterCommit(TFilterAccess& a) override;
};

/** The module if the router may ask for merges (null otherwise). */
std::unique_ptr<CLinkedMergeModule> makeLinkedMergeModule(TFilterAccess& a);
}  // namespace dynslam::ekf
