# drywall-lab: the two commands of the README's quick start are `make lab` and `make test`.
PYTHON ?= python3
VENV ?= .venv
BIN := $(VENV)/bin
# Notebooks honour DRYWALL_FAST=1 (fewer epochs, less data). The test suite runs in fast
# mode unless told otherwise: `make test DRYWALL_FAST=0` executes the notebooks in full.
DRYWALL_FAST ?= 1
export DRYWALL_FAST
# JupyterLab refuses to run as root unless told (containers, CI machines).
LAB_ARGS ?= $(if $(filter 0,$(shell id -u)),--allow-root,)

.PHONY: setup lab demo test corpus default-tagger clean

$(BIN)/.installed: environment.txt pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --upgrade pip
	$(BIN)/pip install -r environment.txt
	touch $@

setup: $(BIN)/.installed  ## create .venv and install environment.txt

lab: setup  ## open the course (notebooks/) in JupyterLab
	$(BIN)/jupyter lab $(LAB_ARGS) notebooks/

demo: setup  ## headless: the course's main results printed in the terminal
	$(BIN)/python -m drywall_lab demo

test: setup  ## the whole test suite, executed notebooks included
	$(BIN)/python -m pytest --nbval-lax --nbval-current-env tests notebooks

corpus: setup  ## regenerate data/corpus from the fixed seed
	$(BIN)/python -m drywall_lab corpus generate

TAGGER_DIR := drywall_lab/models/default_tagger
default-tagger: setup  ## retrain the shipped BiLSTM-CRF (seed 0, ~2 min on 2 CPU cores) and record its scores
	$(BIN)/python -m drywall_lab train bilstm-crf --out $(TAGGER_DIR) --seed 0
	for split in validation test novel; do \
	  printf '%s ' $$split; $(BIN)/python -m drywall_lab evaluate --tagger $(TAGGER_DIR) --split $$split | tail -n 1; \
	done > $(TAGGER_DIR)/scores.txt
	cat $(TAGGER_DIR)/scores.txt

clean:
	rm -rf $(VENV) build .pytest_cache .hypothesis
