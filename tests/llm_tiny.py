"""A tiny causal LM built from a config (no download): a byte-level BPE tokenizer trained on ALFRED
instructions and compact graphs, and a 2-layer Llama. Shared by the language-model tests."""

from __future__ import annotations

from pathlib import Path


def build_tiny_lm(folder: Path) -> Path:
    import torch
    from tokenizers import Tokenizer, decoders, models, pre_tokenizers, trainers
    from transformers import LlamaConfig, LlamaForCausalLM, PreTrainedTokenizerFast

    from models.language.alfred import load_annotations
    from models.language.llm.decoding import prompt_text
    from models.language.llm.graph_text import destination_types, fields_of, target_types

    rows = load_annotations("train")[:400]
    corpus = [prompt_text(r.instruction, r.room_type) + " " + fields_of(r).text() + " |" for r in rows]
    corpus += [" ".join(target_types()), " ".join(destination_types())] * 5
    tok = Tokenizer(models.BPE())
    tok.pre_tokenizer = pre_tokenizers.ByteLevel(add_prefix_space=False)
    tok.decoder = decoders.ByteLevel()
    tok.train_from_iterator(corpus, trainers.BpeTrainer(vocab_size=600, special_tokens=["<eos>", "<pad>"],
                                                        initial_alphabet=pre_tokenizers.ByteLevel.alphabet()))
    fast = PreTrainedTokenizerFast(tokenizer_object=tok, eos_token="<eos>", pad_token="<pad>")
    torch.manual_seed(0)
    config = LlamaConfig(vocab_size=fast.vocab_size, hidden_size=32, intermediate_size=64, num_hidden_layers=2,
                         num_attention_heads=2, num_key_value_heads=1, max_position_embeddings=256,
                         eos_token_id=fast.eos_token_id, pad_token_id=fast.pad_token_id)
    LlamaForCausalLM(config).save_pretrained(folder)
    fast.save_pretrained(folder)
    return folder
