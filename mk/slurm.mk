# Training on a Slurm cluster (tools/slurm/, docs/trainer.md "Training on a
# cluster"): dataset generation as a job array of `trainer --shard K/N`
# tasks, then one job that gathers the shards, fits and exports.
#   make models-slurm SLURM_SHARDS=N [SLURM_ARGS='--partition=... --time=...']
# submits every default model (MODEL_LIST, mk/trainer.mk) and returns;
# tools/slurm/progress shows how far each is.
SLURM_PACKAGES := slurm-wlm munge
SLURM_SHARDS ?= 100
SLURM_CPUS ?= 4

slurm-deps: deps
	@tools/install-deps $(SLURM_PACKAGES)

models-slurm: $(TRAINER)
	@for rm in $(MODEL_LIST); do \
		r=$${rm%%:*}; m=$${rm##*:}; \
		tools/slurm/train --robot $$r --mode $$m --shards $(SLURM_SHARDS) --cpus-per-task $(SLURM_CPUS) \
			--trainer $(TRAINER) --out trainer/datasets/$$r $(if $(MODEL_SAMPLES),--samples $(MODEL_SAMPLES)) \
			$(SLURM_ARGS) || exit 1; \
	done

# The gather step's checks and the scripts run by hand (no Slurm needed), then
# the scripts on a throwaway single-node cluster (skipped, and said why,
# without root or the packages; `make test` installs them).
tests/trainer/test_gather.sh: $(TRAINER)
tests/slurm/test_slurm_scripts.sh: $(TRAINER)
tests/slurm/test_slurm_cluster.sh: $(TRAINER)
test: slurm-deps
TESTS += tests/trainer/test_gather.sh tests/slurm/test_slurm_scripts.sh tests/slurm/test_slurm_cluster.sh

.PHONY: slurm-deps models-slurm
