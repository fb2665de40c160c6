"""Helpers for the course notebooks (issue 13), one module per chapter; every public name is re-exported here,
so ``from drywall_lab.course import X`` and ``course.X`` work whichever module ``X`` lives in.

- :mod:`~drywall_lab.course.common` (every notebook): :func:`fast_mode`, the one reading of ``DRYWALL_FAST``
  (README, "Fast mode"; from ``drywall_lab.fast``), :class:`ExerciseCheck` (from ``drywall_lab.exercise``),
  :func:`percent_table` (tables that read well both as HTML and as text) and the repository's paths.
- :mod:`~drywall_lab.course.taggers` (02, 03, 07): :func:`table_3` (the paper's Table 3 row for a tagger, plus
  ``acc_task``), :func:`scores_on_sets`, :func:`training_curves`, :func:`describe_tagger`.
- :mod:`~drywall_lab.course.study` (02, 03): the project's full NLU study (``results/paper``) and the benchmarks'
  records, in tables and in sentences computed from them.
- :mod:`~drywall_lab.course.annotation` (01): :func:`tag_share_table` (Table 2), the tagging exercise,
  :func:`check_tagging`, entities from scratch (:func:`check_entity_spans`, :func:`entity_scores`) and the
  confusion heatmap (:func:`plot_confusion`).
- :mod:`~drywall_lab.course.bilstm_crf` (02): :func:`crf_transitions` (and its heatmap, :func:`plot_transitions`),
  :func:`check_most_forbidden`, the paper's Figs. 3-4 redrawn (:func:`draw_bilstm_crf`) and the CRF from scratch
  on a three-word toy (path score, forward algorithm, Viterbi: :func:`check_viterbi`).
- :mod:`~drywall_lab.course.bert` (03): the sub-word vote's exercise, :func:`check_vote`, and
  :func:`token_predictions`, :func:`vote_statistics`; sub-word labels from scratch (:func:`check_align_labels`)
  and the paper's Fig. 8 redrawn (:func:`plot_bert_tagger`).
- :mod:`~drywall_lab.course.information_mapping` (04): rule S3's exercise, :func:`check_relative_stud`; the
  paper's layouts step by step (:func:`map_layout`, :func:`show_layout`); every refusal reason with an example
  (:func:`refusal_examples`); a rule path as a flowchart of Figs. 10-12 (:func:`draw_rule_paths`) and rule T2
  from scratch (:func:`check_stacks_of_size`).
- :mod:`~drywall_lab.course.decision` (07): the least expected cost from scratch (:func:`check_expected_cost`)
  and the ablation as a bar chart (:func:`plot_ablation`).

The exercises are in the way of a manipulation course: a skeleton the student completes, a check that says what
is right or wrong. Notebooks 05 and 06's checks are ``drywall_lab.rc.exercises``, notebook 07's
``drywall_lab.field.check_own_instructions``. A notebook's exercise cell holds only the stub (``...``, a function
that raises ``NotImplementedError``); every check then says "NOT ATTEMPTED YET: fill in ..." and the notebook runs
through (``assert check.passed or not check.attempted``). The reference solutions, and the answer keys of the
chapters' end-of-chapter questions, are kept apart in :mod:`drywall_lab.course.solutions` (``ch01`` ... ``ch07``,
:func:`solution_file`): try the exercise first. ``drywall_lab.course`` does not import them.
"""
from __future__ import annotations

from drywall_lab.course.annotation import (ANCHOR_TAGS, ENTITY_EXAMPLE, GUIDELINES, OUTSIDE, PLACEMENT_TAGS,
                                           PRACTICE_DIR, TAGGING_EXERCISE, Span, check_entity_spans, check_tagging,
                                           entity_cases, entity_matches, entity_scores, guideline_headings,
                                           guideline_sections, parse_tagged, plot_confusion, practice_instruction,
                                           reference_entity_spans, tag_share_table)
from drywall_lab.course.bert import (IGNORED_LABEL, WORKED_TAGS, WORKED_WORDS, alignment_cases, alignment_table,
                                     check_align_labels, check_vote, encoder_size, library_alignment,
                                     plot_bert_tagger, token_predictions, vote_cases, vote_statistics)
from drywall_lab.course.decision import (ABLATION_COLUMNS, ACTIONS, TOLERANCE, Answer, CostCase, check_expected_cost,
                                         command_label, decision_inputs, expected_cost_cases, library_decision,
                                         plot_ablation)
from drywall_lab.course.bilstm_crf import (ARCHITECTURE_LAYERS, TOY_EMISSIONS, TOY_TAGS, TOY_WORDS, all_paths,
                                           brute_force_best_path, brute_force_log_partition, check_most_forbidden,
                                           check_viterbi, crf_scores, crf_transitions, draw_bilstm_crf,
                                           forward_log_partition, forward_table, path_score, path_scores,
                                           plot_transitions, reference_most_forbidden, tagged_window,
                                           torchcrf_decode, torchcrf_log_likelihood, toy_crf)
from drywall_lab.course.common import (BENCHMARK_RESULTS, FAST_OFF, FAST_ON, REPO_ROOT, SHARE_COLUMNS, STUDY_DIR,
                                       ExerciseCheck, call_student, compact_figures, compact_png, fast_mode,
                                       is_unattempted, percent_table, solution_file)
from drywall_lab.course.information_mapping import (COUNT_WORDS, RULE_MAPS, SIZE_NUMBERS, SIZE_SITES, GoldLayoutRun,
                                                    RuleStep, check_relative_stud, check_stacks_of_size,
                                                    draw_rule_path, draw_rule_paths, library_stacks_of_size,
                                                    map_layout, refusal_examples, relative_stud_cases, rule_path,
                                                    rule_s3, rule_t2, show_layout, site_with_sizes, size_markup,
                                                    stacks_of_size_cases, unclear_example, words_and_tags)
from drywall_lab.course.study import (PAPER_TAGGER_NAMES, TAGGER_NAMES, accuracy_by_training_size, coref_comparison,
                                      coref_finding, data_efficiency_finding, field_results,
                                      minilm_learning_rate_choice, novel_comparison, novel_finding,
                                      plot_accuracy_by_training_size, read_study_table, study_provenance,
                                      study_settings)
from drywall_lab.course.taggers import describe_tagger, scores_on_sets, table_3, table_3_row, training_curves

__all__ = [
    # common
    "BENCHMARK_RESULTS", "FAST_OFF", "FAST_ON", "REPO_ROOT", "SHARE_COLUMNS", "STUDY_DIR", "ExerciseCheck",
    "call_student", "compact_figures", "compact_png", "fast_mode", "is_unattempted", "percent_table", "solution_file",
    # taggers
    "describe_tagger", "scores_on_sets", "table_3", "table_3_row", "training_curves",
    # study
    "PAPER_TAGGER_NAMES", "TAGGER_NAMES", "accuracy_by_training_size", "coref_comparison", "coref_finding",
    "data_efficiency_finding", "field_results", "minilm_learning_rate_choice", "novel_comparison", "novel_finding",
    "plot_accuracy_by_training_size", "read_study_table", "study_provenance", "study_settings",
    # notebook 01
    "ANCHOR_TAGS", "ENTITY_EXAMPLE", "GUIDELINES", "OUTSIDE", "PLACEMENT_TAGS", "PRACTICE_DIR", "TAGGING_EXERCISE",
    "Span", "check_entity_spans", "check_tagging", "entity_cases", "entity_matches", "entity_scores",
    "guideline_headings", "guideline_sections", "parse_tagged", "plot_confusion", "practice_instruction",
    "reference_entity_spans", "tag_share_table",
    # notebook 02
    "ARCHITECTURE_LAYERS", "TOY_EMISSIONS", "TOY_TAGS", "TOY_WORDS", "all_paths", "brute_force_best_path",
    "brute_force_log_partition", "check_most_forbidden", "check_viterbi", "crf_scores", "crf_transitions",
    "draw_bilstm_crf", "forward_log_partition", "forward_table", "path_score", "path_scores", "plot_transitions",
    "reference_most_forbidden", "tagged_window", "torchcrf_decode", "torchcrf_log_likelihood", "toy_crf",
    # notebook 03
    "IGNORED_LABEL", "WORKED_TAGS", "WORKED_WORDS", "alignment_cases", "alignment_table", "check_align_labels",
    "check_vote", "encoder_size", "library_alignment", "plot_bert_tagger", "token_predictions", "vote_cases",
    "vote_statistics",
    # notebook 04
    "COUNT_WORDS", "RULE_MAPS", "SIZE_NUMBERS", "SIZE_SITES", "GoldLayoutRun", "RuleStep", "check_relative_stud",
    "check_stacks_of_size", "draw_rule_path", "draw_rule_paths", "library_stacks_of_size", "map_layout",
    "refusal_examples", "relative_stud_cases", "rule_path", "rule_s3", "rule_t2", "show_layout", "site_with_sizes",
    "size_markup", "stacks_of_size_cases", "unclear_example", "words_and_tags",
    # notebook 07
    "ABLATION_COLUMNS", "ACTIONS", "TOLERANCE", "Answer", "CostCase", "check_expected_cost", "command_label",
    "decision_inputs", "expected_cost_cases", "library_decision", "plot_ablation",
]
